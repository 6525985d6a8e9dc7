"""The faster comparison of numba's compile flags (dynamics/_speed/flag_values.py) gives
numba's own answers: the expected values come from numba's original `TargetConfig.__eq__` and
`__hash__`, which the module keeps."""

import itertools
import random

import pytest
from numba.core import targetconfig
from numba.core.compiler import Flags

from bearingsim.dynamics._speed import flag_values


def _bool_options():
    return [name for name, option in Flags.options.items() if isinstance(option.default, bool)]


def _random_flags(rng: random.Random) -> Flags:
    flags = Flags()
    for name in rng.sample(_bool_options(), 4):
        setattr(flags, name, rng.random() < 0.5)
    choice = rng.randrange(4)
    if choice == 1:
        flags.fastmath = True
    elif choice == 2:
        flags.fastmath = {"nsz", "arcp"}
    elif choice == 3:
        flags.error_model = rng.choice(["python", "numpy"])
    return flags


def test_importing_the_kernels_installs_it():
    import bearingsim.dynamics.multibody.compiled  # noqa: F401  (imports compile_policy)

    assert targetconfig.TargetConfig.__eq__ is flag_values._eq
    assert targetconfig.TargetConfig.__hash__ is flag_values._hash


def test_equality_and_hash_are_numbas_over_random_flags():
    rng = random.Random(7)
    flags = [_random_flags(rng) for _ in range(60)] + [Flags(), Flags()]
    equal_pairs = 0
    for a, b in itertools.product(flags, repeat=2):
        expected = flag_values._ORIGINAL_EQ(a, b)
        assert flag_values._eq(a, b) == expected, (a, b)
        equal_pairs += expected
    assert equal_pairs > len(flags)  # the sample has equal pairs beyond each with itself
    for a in flags:
        assert flag_values._hash(a) == flag_values._ORIGINAL_HASH(a)


def test_an_option_set_to_its_default_equals_it_unset():
    a, b = Flags(), Flags()
    a.nrt = Flags.options["nrt"].default
    assert flag_values._ORIGINAL_EQ(a, b) and flag_values._eq(a, b)
    a.nrt = not a.nrt
    assert not flag_values._ORIGINAL_EQ(a, b) and not flag_values._eq(a, b)


def test_a_class_with_an_option_served_otherwise_keeps_numbas_methods():
    class Config(targetconfig.TargetConfig):
        level = targetconfig.Option(type=int, default=0, doc="a level")

    Config.level = property(lambda self: 3)  # not the property numba generates
    a, b = Config(), Config()
    a._values["level"] = 1  # what the replaced property hides: both read 3
    assert not flag_values._reads_options_plainly(Config)
    assert flag_values._eq(a, b) == flag_values._ORIGINAL_EQ(a, b) is True
    assert flag_values._hash(a) == flag_values._ORIGINAL_HASH(a)


@pytest.mark.parametrize("other", [None, 0, "Flags"])
def test_comparing_with_something_else_is_numbas_answer(other):
    assert flag_values._eq(Flags(), other) is flag_values._ORIGINAL_EQ(Flags(), other)
