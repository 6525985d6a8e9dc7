"""Linear interpolation in a float32 table by 8-wide gathers (docs/model.md §6.4, *Gathered
viscosity lookup*).

The float32 traction passes read the viscosity of every quadrature node from a table at a
data-dependent position (`traction.fast._viscosity_lookup32`). LLVM does not vectorise that
loop on this project's CPUs: its cost model avoids gathers where Intel's Gather Data Sampling
mitigation made them slow, so the pass stays scalar, one node at a time. `lerp_gather32` writes
the loop in LLVM IR with the `llvm.masked.gather` intrinsic, eight nodes per instruction, and
the same loop one node at a time for the remainder, or for all nodes when `vector` is False.

Both paths compute, per node m,

    f = min(f_index[m], last),   i = floor(f),   out[m] = fma(f - i, flat[2i + 1], flat[2i]) * scale

in float32 with an explicit fused multiply-add (`llvm.fma`), so they give the same bits as each
other, on every CPU, and as the numba loop they replace on a CPU with FMA (there LLVM contracts
its multiply and add into one). Without gathers the time loop now takes neither loop of
`lerp_gather32` but `lerp_rows32`: the row and fraction split in a vectorised pass, the rows
picked as 8-byte words in a scalar pass of nothing but loads and stores (`pick_rows`), the
fma in a vectorised pass -- the same operations, the same bits, and on the AMD EPYC of
2026-11-24 (afternoon) 0.79 instead of 1.12 ns a node. Which is faster depends on the CPU's gather;
`gather_pays` times both once per process and the time loop takes the faster (the choice
changes no result).

The intrinsic's name carries the pointer type: LLVM >= 17 has only opaque pointers (`v8p0`),
the LLVM 14 of older numba typed ones (`v8p0f32`). pyproject.toml requires numba >= 0.62, whose
llvmlite (>= 0.45) brings LLVM 20 or later; the typed name is kept for an older install.
"""

from __future__ import annotations

import functools
import os
import time

import numba
import numpy as np
from llvmlite import binding as llvm_binding
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from bearingsim.dynamics._kernel_options import NO_REFCOUNT, VEC

WIDTH = 8
_OPAQUE_POINTERS = llvm_binding.llvm_version_info[0] >= 17
_GATHER = f"llvm.masked.gather.v{WIDTH}f32.v{WIDTH}p0" + ("" if _OPAQUE_POINTERS else "f32")
_FMA_VECTOR = f"llvm.fma.v{WIDTH}f32"
_FMA = "llvm.fma.f32"

# BEARINGSIM_GATHER = "1" / "0" forces the choice (benchmarks, tests); unset: measured
FORCE_ENV = "BEARINGSIM_GATHER"


@intrinsic
def lerp_gather32(typingctx, f_index, n, flat, last, scale, out, vector):
    """out[m] = fma(f - i, flat[2i + 1], flat[2i]) * scale for m < n (module docstring):
    f_index, flat, out float32 arrays (C-contiguous), n int64, last and scale float32,
    vector bool (8-wide gathers for whole groups of 8, else one node at a time)."""
    sig = types.void(f_index, n, flat, last, scale, out, vector)

    def codegen(context, builder, signature, args):
        fi_v, n_v, flat_v, last_v, scale_v, out_v, vector_v = args
        fi = context.make_array(signature.args[0])(context, builder, fi_v).data
        table = context.make_array(signature.args[2])(context, builder, flat_v).data
        dst = context.make_array(signature.args[5])(context, builder, out_v).data
        f32, i32, i64 = ir.FloatType(), ir.IntType(32), ir.IntType(64)
        vf, vi, vi64 = ir.VectorType(f32, WIDTH), ir.VectorType(i32, WIDTH), ir.VectorType(i64, WIDTH)
        vp = ir.VectorType(f32.as_pointer(), WIDTH)
        vmask = ir.VectorType(ir.IntType(1), WIDTH)
        module = builder.module
        gather = cgutils.get_or_insert_function(module, ir.FunctionType(vf, [vp, i32, vmask, vf]), _GATHER)
        fma_v = cgutils.get_or_insert_function(module, ir.FunctionType(vf, [vf, vf, vf]), _FMA_VECTOR)
        fma_s = cgutils.get_or_insert_function(module, ir.FunctionType(f32, [f32, f32, f32]), _FMA)

        def splat(value, vtype):
            undef = ir.Constant(vtype, ir.Undefined)
            one = builder.insert_element(undef, value, ir.Constant(i32, 0))
            return builder.shuffle_vector(one, undef, ir.Constant(ir.VectorType(i32, WIDTH), [0] * WIDTH))

        # whole groups of WIDTH nodes through gathers (none when vector is False)
        groups = builder.select(vector_v, builder.udiv(n_v, ir.Constant(i64, WIDTH)), ir.Constant(i64, 0))
        last_s, scale_s = splat(last_v, vf), splat(scale_v, vf)
        everything = ir.Constant(vmask, [1] * WIDTH)
        undef_f = ir.Constant(vf, ir.Undefined)
        base = splat(builder.ptrtoint(table, i64), vi64)
        stride = splat(ir.Constant(i64, 4), vi64)  # bytes per float32
        with cgutils.for_range(builder, groups) as loop:
            first = builder.mul(loop.index, ir.Constant(i64, WIDTH))
            f = builder.load(builder.bitcast(builder.gep(fi, [first]), vf.as_pointer()), align=4)
            f = builder.select(builder.fcmp_ordered("<", f, last_s), f, last_s)
            i = builder.fptoui(f, vi)
            frac = builder.fsub(f, builder.uitofp(i, vf))
            j = builder.zext(builder.shl(i, splat(ir.Constant(i32, 1), vi)), vi64)
            at_j = builder.add(base, builder.mul(j, stride))
            at_j1 = builder.add(at_j, stride)
            e0 = builder.call(gather, [builder.inttoptr(at_j, vp), ir.Constant(i32, 4), everything, undef_f])
            e1 = builder.call(gather, [builder.inttoptr(at_j1, vp), ir.Constant(i32, 4), everything, undef_f])
            value = builder.fmul(builder.call(fma_v, [frac, e1, e0]), scale_s)
            builder.store(value, builder.bitcast(builder.gep(dst, [first]), vf.as_pointer()), align=4)
        # the rest one node at a time, the same operations
        start = builder.mul(groups, ir.Constant(i64, WIDTH))
        with cgutils.for_range_slice(builder, start, n_v, ir.Constant(i64, 1), inc=True) as (m, _):
            f = builder.load(builder.gep(fi, [m]))
            f = builder.select(builder.fcmp_ordered("<", f, last_v), f, last_v)
            i = builder.fptoui(f, i32)
            frac = builder.fsub(f, builder.uitofp(i, f32))
            j = builder.zext(builder.shl(i, ir.Constant(i32, 1)), i64)
            e0 = builder.load(builder.gep(table, [j]))
            e1 = builder.load(builder.gep(table, [builder.add(j, ir.Constant(i64, 1))]))
            builder.store(builder.fmul(builder.call(fma_s, [frac, e1, e0]), scale_v), builder.gep(dst, [m]))
        return context.get_dummy_value()

    return sig, codegen


@numba.njit(cache=True, inline="always")
def last_position32(flat):
    """The largest table position a lookup takes, in float32: just short of the last row of
    flat (rows (v_i, v_(i+1) - v_i) flattened), so that its row is the last full interval.
    Every lookup route clamps at this one value: the same bits need the same clamp."""
    return np.float32(flat.size // 2 - 1.000001)


@numba.njit(cache=True, inline="always")
def split_position32(f_index, last):
    """(i, f - i) of f = min(f_index, last): the row (uint32) and the fraction within it
    (float32), as `lerp_gather32` splits them (fptoui, uitofp, fsub)."""
    f = min(f_index, last)
    i = np.uint32(f)
    return i, f - np.float32(i)


@numba.njit(cache=True, inline="always")
def lerp_picked32(pair, m, frac, scale):
    """fma(frac, v_(i+1) - v_i, v_i) * scale from node m's picked row, `pair` being the picked
    rows viewed as float32 (v_i, v_(i+1) - v_i) pairs; LLVM contracts the multiply and add as
    `lerp_gather32` fuses them explicitly."""
    return (pair[2 * m] + frac * pair[2 * m + 1]) * scale


@numba.njit(**NO_REFCOUNT)
def lerp_table32(f_index, n, flat, inv_scale, out, vector):
    """`lerp_gather32` with last = `last_position32(flat)` and scale = inv_scale as float32."""
    lerp_gather32(f_index, np.int64(n), flat, last_position32(flat), np.float32(inv_scale), out, vector)


@numba.njit(**VEC)
def pick_rows(row, n, rows, picked):
    """picked[m] = rows[row[m]] for m < n: the table's rows (v_i, v_(i+1) - v_i) read as one
    8-byte word each (`flat.view(np.int64)`), row uint32, picked int64. LLVM leaves this loop
    scalar too, but with the index arithmetic moved into vectorised passes around it the whole
    lookup costs less than the one-node-at-a-time loop (2026-11-24, AMD EPYC, 240-node contacts:
    0.79 against 1.12 ns a node, `lerp_rows32`)."""
    for m in range(n):
        picked[m] = rows[np.uint64(row[m])]


@numba.njit(**VEC)
def lerp_rows32(f_index, n, flat, inv_scale, out, row, frac, picked):
    """`lerp_table32` without gathers in three passes -- split f = min(f_index[m], last) into
    its row and fraction (vectorised), `pick_rows` (scalar loads), fma(f - i, v_(i+1) - v_i,
    v_i) * scale (vectorised) -- with the same operations, so the same bits on a CPU with FMA.
    row (uint32), frac (float32), picked (int64): scratch of length >= n. The float32 traction
    passes fuse the first and last pass into their neighbours (`traction.fast`)."""
    last = last_position32(flat)
    scale = np.float32(inv_scale)
    for m in range(n):
        row[m], frac[m] = split_position32(f_index[m], last)
    pick_rows(row, n, flat.view(np.int64), picked)
    pair = picked.view(np.float32)
    for m in range(n):
        out[m] = lerp_picked32(pair, m, frac[m], scale)


@numba.njit(**NO_REFCOUNT)
def _repeat_lookup(f_index, n, flat, out, vector, repeats, row, frac, picked):
    for _ in range(repeats):
        if vector:
            lerp_table32(f_index, n, flat, 1.0, out, True)
        else:
            lerp_rows32(f_index, n, flat, 1.0, out, row, frac, picked)
    return out[0]


@functools.lru_cache(maxsize=None)
def gather_pays() -> bool:
    """Whether the gathered lookup is faster on this CPU than the lookup without gathers the
    float32 traction takes otherwise (`lerp_rows32`: rows picked in a scalar pass of loads; module
    docstring), measured once per process: 240 nodes, as many as a contact of the
    reference bearing, in a table of 4096 rows; the best of 15 alternated rounds of 400 calls
    each (~10 ms in all). The gathers must save 10 % to be taken. `BEARINGSIM_GATHER` = 1 or 0
    decides instead."""
    forced = os.environ.get(FORCE_ENV, "").strip()
    if forced in ("0", "1"):
        return forced == "1"
    rng = np.random.default_rng(0)
    n = 240
    flat = rng.uniform(1e-3, 1.0, 2 * 4096).astype(np.float32)
    f_index = rng.uniform(0.0, 3000.0, n).astype(np.float32)
    out = np.empty(n, dtype=np.float32)
    scratch = (np.empty(n, dtype=np.uint32), np.empty(n, dtype=np.float32), np.empty(n, dtype=np.int64))
    best = {True: np.inf, False: np.inf}
    for vector in (True, False):
        _repeat_lookup(f_index, n, flat, out, vector, 10, *scratch)  # compile, warm
    for _ in range(15):
        for vector in (True, False):
            t0 = time.perf_counter()
            _repeat_lookup(f_index, n, flat, out, vector, 400, *scratch)
            best[vector] = min(best[vector], time.perf_counter() - t0)
    return best[True] <= 0.9 * best[False]
