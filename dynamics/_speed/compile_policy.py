"""Compile policy of the numba kernels, defined once: caching, reference counting, fast-math.

numba keeps a reference count on every array a function receives or slices (a view) and
updates it with an atomic add inside a non-inlined call (NRT_incref / NRT_decref); its
pruning pass leaves most of these in place across calls, and in the force kernel of the
reference bearing they were the largest single cost in a profile (docs/performance.md).
Kernels that allocate nothing and return no array need none of it (`NO_REFCOUNT`). The
compiled time loop (`multibody.compiled.hht_chunk`) and the block-arrow solve use it too.

With `_nrt=False` numba refuses to compile an allocation, an array return, or a call to
a function that returns an array, so these kernels can only borrow the caller's arrays
(and views of them), which outlive the call. Named bundles of such arrays (NamedTuples,
dynamics/bearing/bundles.py) are plain structs of borrowed arrays: these kernels take them,
and build them from views, without any reference counting. tests/test_bearing_model.py
checks that the arrays passed through the model keep their reference counts.

These are numba's public `jit` options only: importing the kernels changes nothing in numba
itself, so other numba code in the same process compiles as it would without bearingsim
(tests/test_numba_untouched.py).
"""

# Every kernel: cached, and without the C-callable wrapper numba otherwise compiles for each
# function so that it can be passed around as a first-class function value (a compile cost on a
# machine's first run, docs/performance.md); only `FIRST_CLASS` kernels are passed that way.
KERNEL = {"cache": True, "no_cfunc_wrapper": True}

NO_REFCOUNT = {**KERNEL, "_nrt": False}

# A kernel that the compiled time loop receives as a first-class function value (the force kernel,
# the accepted-step hook; multibody/compiled.py, `KernelFunction`): it keeps its C-callable wrapper.
FIRST_CLASS = {**NO_REFCOUNT, "no_cfunc_wrapper": False}

# Kernels that allocate and are called from a `NO_REFCOUNT` kernel: numba compiles a callee with
# the flags of the caller it is first typed from unless the callee states its own, so these say
# that they keep reference counting.
WITH_REFCOUNT = {**KERNEL, "_nrt": True}

# Kernels that only other kernels call, with bundles of many arrays: no Python entry either, whose
# unboxing code for those bundles is a large part of their compile.
INTERNAL = {"no_cpython_wrapper": True}

# The vectorised passes over arrays (dynamics/_speed/simd_math.py, traction/nodes.py, traction/fast.py,
# the film batch): fast-math so that LLVM vectorises their loops and reductions, without
# nnan/ninf because callers hold inf in some lanes (`traction.nodes.pole_position` returns inf
# for "no pole", which must compare correctly), and numpy's error model so that `/` carries no
# zero-division branch.
VEC = {"fastmath": {"nsz", "arcp", "contract", "afn", "reassoc"}, "error_model": "numpy", **NO_REFCOUNT}

# A vectorised pass whose results must not depend on where it was compiled: with "contract" LLVM
# may fuse multiply-adds differently in a kernel's own library and in the copies linked into its
# callers, and a process that compiled the kernels then runs other bits than one that loaded them
# from the cache (docs/model.md §9: `traction.fast._slip_and_table_index`).
VEC_UNFUSED = {**VEC, "fastmath": VEC["fastmath"] - {"contract"}}
