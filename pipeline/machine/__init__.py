"""What this machine provides: compiled-kernel caches, cores, system libraries."""
