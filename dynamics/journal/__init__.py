"""Cage–guiding-race contact as a short journal bearing (docs/model.md §8): the hybrid
film/metal law (`hybrid`) and the dry line contact it blends into (`dry`)."""
