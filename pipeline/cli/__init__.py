"""The command line: `bearingsim` commands, their options and tables, warm-up."""
