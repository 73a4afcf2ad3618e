"""A settings mixin (annotations of bpy properties) as the scripting API sees it: names in
declaration order, defaults, and completion of a script's keyword arguments.

Shared by the knit settings (`properties.KnitSettingsMixin`) and the plush settings
(`plush.PlushSettingsMixin`).
"""

import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from bpy.props import FloatProperty, FloatVectorProperty, StringProperty


@dataclass(frozen=True)
class SettingsSchema:
    #: What the settings are of ("knit", "plush"), for messages.
    what: str
    #: A class whose annotations are bpy property definitions.
    mixin: type
    #: Keywords renamed since a release, old name to new: still accepted from scripts, with a
    #: DeprecationWarning.
    renamed: Mapping[str, str] = field(default_factory=dict)

    @property
    def names(self) -> tuple[str, ...]:
        """The settings' names, in declaration order (the scripting API's keywords)."""
        return tuple(self.mixin.__annotations__)

    @property
    def float_names(self) -> tuple[str, ...]:
        """The settings Blender stores as single-precision floats."""
        return tuple(
            name
            for name, prop in self.mixin.__annotations__.items()
            if prop.function in (FloatProperty, FloatVectorProperty)
        )

    def defaults(self) -> dict[str, Any]:
        """Each setting's default value, as the scripting API applies it."""
        out: dict[str, Any] = {}
        for name, prop in self.mixin.__annotations__.items():
            value = prop.keywords.get("default")
            if value is None:
                value = "" if prop.function is StringProperty else 0
            out[name] = tuple(value) if isinstance(value, tuple | list) else value
        return out

    def complete(self, settings: Mapping[str, Any]) -> dict[str, Any]:
        """``settings`` with every missing one at its default; unknown names are a TypeError.

        Blender stores float settings in single precision. Rounding a script's values the same
        way makes a result built from keyword arguments and one rebuilt later from the stored
        settings bit-identical, as they are for the operator.
        """
        settings = dict(settings)
        for old, new in self.renamed.items():
            if old in settings:
                warnings.warn(
                    f"the {self.what} setting {old} is now called {new}",
                    DeprecationWarning,
                    stacklevel=3,
                )
                settings.setdefault(new, settings.pop(old))
        unknown = sorted(set(settings) - set(self.names))
        if unknown:
            raise TypeError(
                f"unknown {self.what} setting(s) {', '.join(unknown)}; "
                f"known: {', '.join(self.names)}"
            )
        merged = self.defaults() | dict(settings)
        for name in self.float_names:
            value = merged[name]
            if isinstance(value, int | float):
                merged[name] = float(np.float32(value))
            else:  # a colour: tuple, list or Blender's property array
                merged[name] = tuple(float(np.float32(x)) for x in value)
        return merged

    def read(self, stored: Any) -> dict[str, Any]:
        """The settings stored on a property group, as keyword arguments."""
        out: dict[str, Any] = {}
        for name in self.names:
            value = getattr(stored, name)
            out[name] = value if isinstance(value, str | int | float) else tuple(value)
        return out
