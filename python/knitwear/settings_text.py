"""Each setting of the core's table (`knitwear.settings()`, declared once in `src/settings.rs`)
in words: its default and its range with the unit. `help(knitwear.knit)` and the manual's
settings reference (`scripts/settings_table.py` writes docs/settings.md) both read these, so
the two always say the same."""

import math
import textwrap
from typing import Any


def number(value: Any, kind: str) -> str:
    """A default or a bound as the docs print it: `on`/`off`, `1 000 000`, `> 0`, `0.5`."""
    if value is None:
        return "-"
    if kind == "bool":
        return "on" if value else "off"
    if kind == "int":
        return f"{int(value):,}".replace(",", " ")
    if isinstance(value, float) and 0 < abs(value) < 1e-30:
        return "> 0"
    return f"{value:g}"


def value_range(setting: dict[str, Any]) -> str:
    """The values a setting takes, with its unit: `3 .. 64 vertices`, `> 0 stitches per 10 cm`."""
    kind = setting["type"]
    if kind == "bool":
        return "on / off"
    lo, hi = setting["min"], setting["max"]
    if lo is not None and 0 < lo < 1e-30:
        text = "> 0" if hi is None else f"> 0 .. {number(hi, kind)}"
    elif lo is None:
        text = "any" if hi is None else f"up to {number(hi, kind)}"
    elif hi is None or (isinstance(hi, float) and math.isinf(hi)):
        text = f"{number(lo, kind)} or more"
    else:
        text = f"{number(lo, kind)} .. {number(hi, kind)}"
    return f"{text} {setting['unit']}".strip()


def default(setting: dict[str, Any]) -> str:
    """The core's default in words (`automatic` where the core works it out)."""
    if setting["default"] is None:
        return "automatic"
    return number(setting["default"], setting["type"])


def help_text(settings: list[dict[str, Any]]) -> str:
    """One paragraph per setting, as `help()` shows a function's arguments."""
    lines = []
    for s in settings:
        name = s["core_keyword"] or f"{s['part_of']} ({s['name']})"
        lines.append(f"{name}")
        text = f"{s['doc']}. Default {default(s)}; {value_range(s)}."
        lines += textwrap.wrap(
            text, 84, initial_indent="    ", subsequent_indent="    ", break_on_hyphens=False
        )
    return "\n".join(lines)
