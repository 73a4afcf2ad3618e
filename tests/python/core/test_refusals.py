"""Issue 18's bad inputs, answered by a `KnitError` that names the setting, its value and its
range, before anything large is allocated: never an abort, a segfault, a hang or a bare
`OverflowError` / `UnicodeEncodeError` / `TypeError` from inside the binding."""

from __future__ import annotations

import os
from pathlib import Path

import knitwear
import numpy as np
import pytest


def sheet(size: float = 0.05, n: int = 12) -> knitwear.GridSurface:
    u, v = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    pos = np.stack([u * size, v * size, np.zeros_like(u)], axis=-1).astype(np.float32)
    nrm = np.zeros_like(pos)
    nrm[..., 2] = 1.0
    return knitwear.GridSurface(pos, nrm)


def checker_chart(n: int) -> str:
    """An n x n chart of 2 x 2 knit and purl blocks: its smallest repeat is 4 x 4."""
    return "\n".join("".join("kp"[(r // 2 + c // 2) % 2] for c in range(n)) for r in range(n))


STOCKINETTE = knitwear.Pattern.preset("stockinette")


# --- Charts and Knitspeak: sizes, nesting, files ---------------------------------------------


def test_a_chart_over_the_repeat_limit_is_refused_before_it_is_read() -> None:
    with pytest.raises(knitwear.PatternError, match=r"1024 stitches x 1024 rows.*at most 256"):
        knitwear.Pattern.from_chart(checker_chart(1024))


def test_a_large_chart_knits_through_its_smallest_repeat() -> None:
    big = knitwear.Pattern.from_chart(checker_chart(64))
    small = knitwear.Pattern.from_chart(checker_chart(4))
    a = knitwear.knit(sheet(), big, courses=16, wales=16)
    b = knitwear.knit(sheet(), small, courses=16, wales=16)
    # The same fabric: 64 x 64 is sixteen repeats of the 4 x 4 motif each way.
    assert np.array_equal(a.vertices, b.vertices)


def test_a_large_chart_with_no_small_repeat_still_knits() -> None:
    rng = np.random.default_rng(7)
    rows = ["".join(rng.choice(["k", "p"], 40)) for _ in range(40)]
    r = knitwear.knit(sheet(), knitwear.Pattern.from_chart("\n".join(rows)), courses=12, wales=12)
    assert r.stats["stitches"] == 144
    assert np.isfinite(r.vertices).all() and len(r.triangles) > 0


def test_deeply_nested_brackets_are_a_pattern_error_not_a_stack_overflow() -> None:
    text = "Row 1: " + "[" * 20000 + "k1" + "]" * 20000
    with pytest.raises(knitwear.PatternError, match="nest more than 16 deep"):
        knitwear.Pattern.from_knitspeak(text)
    # Two deep, as written patterns nest, still reads.
    knitwear.Pattern.from_knitspeak("Row 1: *[k1, (p1, k1) 2 times] 2 times; rep from *.")


def test_row_numbers_beyond_the_limit_say_so() -> None:
    with pytest.raises(knitwear.PatternError, match="row 100000000 is outside the rows 1 to 1024"):
        knitwear.Pattern.from_knitspeak("Rows 1-100000000: k1")


def test_a_cross_too_wide_is_explained_not_suggested_as_itself() -> None:
    with pytest.raises(knitwear.PatternError) as e:
        knitwear.Pattern.from_knitspeak("Row 1: 7/7 RC")
    assert "at most 6 stitches over 6" in str(e.value)
    assert "did you mean" not in str(e.value)


def test_a_centre_cross_too_wide_is_explained() -> None:
    # 4/3/4: each side group travels 7 columns, one more than any plain cross.
    with pytest.raises(knitwear.PatternError) as e:
        knitwear.Pattern.from_knitspeak("Row 1: 4/3/4 LPC")
    assert "m + c and c + n are at most 6" in str(e.value)
    assert "did you mean" not in str(e.value)
    # The widest that reads.
    knitwear.Pattern.from_knitspeak("Row 1 (RS): 3/3/3 LPC, p2.\nRow 2 (WS): K2, p3, k3, p3.")


def test_an_endless_or_huge_file_is_refused_without_reading_it_all() -> None:
    with pytest.raises(knitwear.PatternError, match="larger than the 4 MiB"):
        knitwear.Pattern.from_file("/dev/zero")


def test_a_folder_is_not_a_pattern_file(tmp_path: Path) -> None:
    with pytest.raises(knitwear.PatternError, match="folder"):
        knitwear.Pattern.from_file(tmp_path)


def test_paths_as_bytes_and_pathlike_read_the_file(tmp_path: Path) -> None:
    f = tmp_path / "rib.ks"
    f.write_text("Row 1: *k1, p1; rep from *.", encoding="utf-8")
    for path in (f, str(f), bytes(f)):
        assert knitwear.Pattern.from_file(path).width == 2
    with pytest.raises(knitwear.PatternError, match="str, bytes or os.PathLike"):
        knitwear.Pattern.from_file(3.5)  # type: ignore[arg-type]


def test_a_file_that_is_not_utf8_names_the_byte(tmp_path: Path) -> None:
    f = tmp_path / "latin1.ks"
    f.write_bytes("Row 1: k1 \u00e9".encode("latin-1"))
    with pytest.raises(knitwear.PatternError, match="not UTF-8"):
        knitwear.Pattern.from_file(f)


@pytest.mark.parametrize(
    "call",
    [
        knitwear.Pattern.from_knitspeak,
        knitwear.Pattern.from_chart,
        knitwear.Pattern.from_text,
        knitwear.Pattern.looks_like_knitspeak,
    ],
)
def test_a_lone_surrogate_is_a_pattern_error(call) -> None:  # noqa: ANN001
    with pytest.raises(knitwear.PatternError, match="lone surrogate"):
        call("Row 1: k\udc80")


# --- Integers out of any Rust type's range ---------------------------------------------------


@pytest.mark.parametrize(
    ("keyword", "value"),
    [
        ("seed", -1),
        ("seed", 2**64),
        ("budget_bytes", 2**70),
        ("courses", 2**64),
        ("wales", -3),
        ("ring_segments", 2**200),
        ("samples_per_loop", -(2**70)),
        ("threads", 0),
    ],
)
def test_integer_settings_out_of_range_name_themselves(keyword: str, value: int) -> None:
    with pytest.raises(knitwear.ParameterError, match=keyword):
        knitwear.knit(sheet(), STOCKINETTE, **{"courses": 8, "wales": 8, keyword: value})


def test_an_integer_setting_given_a_float_is_a_parameter_error() -> None:
    with pytest.raises(knitwear.ParameterError, match="pass an int"):
        knitwear.knit(sheet(), STOCKINETTE, courses=8.5)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("keyword", "value"),
    [
        ("gauge", (20.0, 28.0, 1.0)),
        ("gauge", "20x28"),
        ("stitch_size", (0.004,)),
        ("detail_px", (1.0, 2.0)),
        ("mid_quality", (2**70, 4, True)),
        ("far_quality", (6, 3)),
    ],
)
def test_tuple_settings_of_the_wrong_shape_name_themselves(keyword: str, value: object) -> None:
    with pytest.raises(knitwear.ParameterError, match=keyword):
        knitwear.Knit(sheet(), STOCKINETTE, **{"courses": 8, "wales": 8, keyword: value})


def test_plush_and_measure_tuple_arguments_of_the_wrong_shape() -> None:
    for keyword, value in (
        ("noise_scales", [1, 2**64]),
        ("noise_size", (8, 8, 8)),
        ("lean", "up"),
        ("eye", [0.0, "a", 1.0]),
    ):
        with pytest.raises(knitwear.ParameterError, match=keyword):
            knitwear.plush(sheet(), courses=4, wales=4, **{keyword: value})
    with pytest.raises(knitwear.ParameterError, match="scales"):
        knitwear.fractal_noise(8, scales=[2**63])
    r = knitwear.knit(sheet(), STOCKINETTE, courses=4, wales=4)
    with pytest.raises(knitwear.ParameterError, match="bounds"):
        knitwear.measure_cover(r, (0.0, 0.0, 1.0))


def test_other_integer_arguments_out_of_range() -> None:
    with pytest.raises(knitwear.ParameterError, match="rows_each"):
        knitwear.ColorPattern.stripes([[1, 0, 0], [0, 0, 1]], rows_each=-2)
    with pytest.raises(knitwear.ParameterError, match="width"):
        knitwear.knit_texture(sheet(), STOCKINETTE, width=-1, height=8)
    with pytest.raises(knitwear.ParameterError, match="camera resolution width"):
        knitwear.Camera(np.eye(4, dtype=np.float32), np.array([0, 0, 1, 0]), (-1, 480))
    with pytest.raises(knitwear.ParameterError, match="seed"):
        knitwear.fractal_noise(8, seed=-1)
    with pytest.raises(knitwear.ParameterError, match="seed"):
        knitwear.plush(sheet(), courses=4, wales=4, seed=2**64)


# --- Cameras and the hidden-yarn pass --------------------------------------------------------


def filling_camera(resolution: int, views: int = 1) -> knitwear.Camera:
    """An orthographic camera whose frame the 5 cm sheet fills."""
    m = np.eye(4, dtype=np.float32)
    m[0, 0] = m[1, 1] = 40.0
    m[0, 3] = m[1, 3] = -1.0
    m[2, 2] = 0.1
    eye = np.array([0, 0, 1, 0], np.float32)
    if views > 1:
        return knitwear.Camera(np.tile(m, (views, 1, 1)), np.tile(eye, (views, 1)), (640, 480))
    return knitwear.Camera(m, eye, (resolution, resolution))


def test_the_hidden_yarn_pass_keeps_to_the_budget() -> None:
    with pytest.raises(knitwear.BudgetError, match="hidden-yarn pass"):
        knitwear.knit(
            sheet(),
            STOCKINETTE,
            courses=20,
            wales=20,
            camera=filling_camera(16384),
            cull_hidden=True,
            budget_bytes=100_000_000,
        )


def test_a_sample_grid_too_large_to_rasterise_in_time_is_refused() -> None:
    with pytest.raises(knitwear.ParameterError, match="hidden_supersampling"):
        knitwear.Knit(
            sheet(), STOCKINETTE, courses=8, wales=8, camera=filling_camera(65536), cull_hidden=True
        )


def test_too_many_views_are_refused() -> None:
    with pytest.raises(knitwear.ParameterError, match="at most 2048 views"):
        knitwear.Knit(sheet(), STOCKINETTE, courses=8, wales=8, camera=filling_camera(0, 10_000))


def test_degenerate_cameras_are_refused() -> None:
    singular = np.eye(4, dtype=np.float32)
    singular[1, 1] = 0.0
    with pytest.raises(knitwear.ParameterError, match="singular"):
        knitwear.Knit(
            sheet(),
            STOCKINETTE,
            courses=8,
            wales=8,
            camera=knitwear.Camera(singular, np.array([0, 0, 1, 0]), (64, 64)),
        )
    for w in (2.0, -1.0):
        with pytest.raises(knitwear.ParameterError, match="w = "):
            knitwear.Knit(
                sheet(),
                STOCKINETTE,
                courses=8,
                wales=8,
                camera=knitwear.Camera(np.eye(4), np.array([0, 0, 1, w]), (64, 64)),
            )


# --- Sizes checked against the surface -------------------------------------------------------


def test_a_stitch_larger_than_the_surface_is_refused() -> None:
    with pytest.raises(knitwear.ParameterError, match=r"stitch_size \(100 x 100\)"):
        knitwear.knit(sheet(), STOCKINETTE, stitch_size=(100.0, 100.0))


def test_a_pile_longer_than_the_fabric_is_refused() -> None:
    with pytest.raises(knitwear.ParameterError, match="pile_length"):
        knitwear.plush(sheet(), courses=8, wales=8, pile_length=1e30)


def test_a_named_pipe_is_refused_without_waiting_for_a_writer(tmp_path: Path) -> None:
    fifo = tmp_path / "pattern.ks"
    os.mkfifo(fifo)
    with pytest.raises(knitwear.PatternError, match="pipe"):
        knitwear.Pattern.from_file(fifo)


def test_check_budget_is_the_check_knit_makes_first() -> None:
    small = knitwear.check_budget(STOCKINETTE, 8, 8)
    assert small == knitwear.check_budget(STOCKINETTE, 8, 8, ring_segments=6)
    assert small < knitwear.check_budget(STOCKINETTE, 8, 8, ring_segments=12)
    with pytest.raises(knitwear.BudgetError, match="stitches would need") as by_check:
        knitwear.check_budget(STOCKINETTE, 100_000, 140_000)
    with pytest.raises(knitwear.BudgetError) as by_knit:
        knitwear.Knit(sheet(), STOCKINETTE, courses=100_000, wales=140_000)
    assert str(by_check.value) == str(by_knit.value)
    with pytest.raises(knitwear.BudgetError):
        knitwear.check_budget(STOCKINETTE, 8, 8, budget_bytes=small - 1)
    with pytest.raises(knitwear.ParameterError, match="ring_segments"):
        knitwear.check_budget(STOCKINETTE, 8, 8, ring_segments=1)
    with pytest.raises(knitwear.ParameterError, match="courses"):
        knitwear.check_budget(STOCKINETTE, 0, 8)
