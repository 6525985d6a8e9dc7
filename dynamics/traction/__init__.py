"""Traction of an EHD point contact (docs/model.md §6.4): the laws (`laws`), the reference
quadrature (`quadrature`), the fast pole-centred rule the time loop uses (`fast`) and the
placement of its nodes (`nodes`)."""
