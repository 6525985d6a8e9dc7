"""Compile policy of the numba kernels, defined once: caching, reference counting, fast-math.

numba keeps a reference count on every array a function receives or slices (a view) and
updates it with an atomic add inside a non-inlined call (NRT_incref / NRT_decref); its
pruning pass leaves most of these in place across calls, and in the force kernel of the
reference bearing they were the largest single cost in a profile (docs/performance.md).
Kernels that allocate nothing and return no array need none of it (`NO_REFCOUNT`). The
compiled time loop (`bearing.model.bearing_chunk`) and the block-arrow solve use it too.

With `_nrt=False` numba refuses to compile an allocation, an array return, or a call to
a function that returns an array, so these kernels can only borrow the caller's arrays
(and views of them), which outlive the call. Named bundles of such arrays (NamedTuples,
dynamics/bearing/bundles.py) are plain structs of borrowed arrays: these kernels take them,
and build them from views, without any reference counting. tests/test_bearing_model.py
checks that the arrays passed through the model keep their reference counts.
"""

NO_REFCOUNT = {"cache": True, "_nrt": False}

# The vectorised passes over arrays (dynamics/_speed/simd_math.py, traction/nodes.py, traction/fast.py,
# the film batch): fast-math so that LLVM vectorises their loops and reductions, without
# nnan/ninf because callers hold inf in some lanes (`traction.nodes.pole_position` returns inf
# for "no pole", which must compare correctly), and numpy's error model so that `/` carries no
# zero-division branch.
VEC = {"fastmath": {"nsz", "arcp", "contract", "afn", "reassoc"}, "error_model": "numpy", **NO_REFCOUNT}
