"""Performance helpers of the numba kernels, in one private place: compile policy
(`compile_policy`: numba's public jit options, nothing of numba replaced), cache-line-aligned
scratch (`aligned`), vectorisable exp and log over arrays (`simd_math`) and the float32 table
lookup (`table_lookup`).

Physics modules take their compile options from `compile_policy`; the rest serves the engines
(the fast traction, the film batch), which are the only places that know about vector widths,
precision and alignment. docs/performance.md has the measurements behind them.
"""
