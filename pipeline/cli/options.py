"""Typer commands that take their options as one settings object.

Typer builds a command's options from the parameters of its function, one parameter an
option; it has no way of its own to read them from a dataclass (fastapi/typer#154). A command
of many options would then be a function of many parameters. `flat_options` lets the function
take a frozen dataclass instead: it shows typer a signature in which every field of that
dataclass is an option of its own (the field's annotation, typer.Option included, and its
default), and calls the function with the dataclass built from them. The command line, its
help and its defaults are what they would be with the fields written out as parameters.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import typing


def flat_options(command):
    """`command` with each parameter annotated by a dataclass shown to typer as that
    dataclass's fields, in their order, each an option (keyword-only)."""
    hints = typing.get_type_hints(command, include_extras=True)
    shown, bundles = [], {}
    for param in inspect.signature(command).parameters.values():
        bundle = hints.get(param.name)
        if not (inspect.isclass(bundle) and dataclasses.is_dataclass(bundle)):
            shown.append(param.replace(annotation=hints.get(param.name, param.annotation)))
            continue
        fields = typing.get_type_hints(bundle, include_extras=True)
        names = [f.name for f in dataclasses.fields(bundle)]
        bundles[param.name] = (bundle, names)
        shown += [inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=f.default, annotation=fields[f.name])
                  for f in dataclasses.fields(bundle)]

    @functools.wraps(command)
    def run(**values):
        for name, (bundle, names) in bundles.items():
            values[name] = bundle(**{field: values.pop(field) for field in names})
        return command(**values)

    run.__signature__ = inspect.Signature(shown, return_annotation=inspect.Signature.empty)
    run.__annotations__ = {p.name: p.annotation for p in shown}
    return run
