"""The Python module `sandpaper` (bindings/python), as an experimenter would use it: compile by name
and by text, errors carrying diagnostics, explain as a dict, the force field and a run's trace as
numpy arrays, and playing while Python goes on. Run by ctest (python.module) with PYTHONPATH set to
the build's python/ folder."""
import pathlib
import re
import threading
import time

import numpy as np
import pytest

import sandpaper


@pytest.fixture(scope="module")
def lib():
    return sandpaper.Library()


def test_compiles_a_library_entry_with_its_calibrated_numbers(lib):
    m = lib.compile("corduroy")
    assert m.name == "corduroy"
    assert 0.1 < m.compiled_max_lateral_force_N < 10.0
    assert m.compiled_roughness > 0
    assert m.size_m[0] > 0 and m.size_m[1] > 0
    assert "corduroy" in lib.names()


def test_a_roughness_level_is_stronger_the_coarser_it_is(lib):
    levels = lib.roughness_levels()
    assert "coarse" in levels and "fine" in levels
    assert lib.roughness_level("coarse").compiled_max_lateral_force_N > lib.roughness_level("fine").compiled_max_lateral_force_N


def test_a_failed_compile_raises_with_the_diagnostics_as_data(lib):
    with pytest.raises(sandpaper.CompileError) as info:
        lib.compile("grating period 2.5 parsecs")
    err = info.value
    assert isinstance(err, sandpaper.Error)
    assert "<compile>:1:" in str(err) and "^" in str(err)
    assert err.diagnostics and err.diagnostics[0]["severity"] == "error"
    assert err.diagnostics[0]["code"].startswith("E")
    assert err.diagnostics[0]["line"] == 1


def test_every_calibrated_dimension_has_named_levels(lib):
    # calibration/levels/: four equal log steps over each map's domain, weakest first.
    assert lib.levels("softness") == ["very-firm", "firm", "medium", "soft", "very-soft"]
    assert lib.levels("slipperiness")[-1] == "very-slippery"
    assert lib.levels("bumpiness") == []
    soft = lib.level("softness", "soft")
    assert any("harper-stevens1964" in w for w in soft.warnings)  # W0321 names the map
    target = soft.explain()["percepts"][0]
    assert target["map"]["id"] == "harper-stevens1964" and target["parameter_unit"] == "N/m"
    assert target["parameter_value"] == pytest.approx(20 * 0.630957 ** (-1 / 0.8), rel=1e-9)  # 35.57 N/m
    with pytest.raises(sandpaper.UnknownLevel) as info:
        lib.level("viscosity", "thickk")
    assert 'did you mean "thick"' in str(info.value)


def test_an_unknown_level_names_the_known_ones(lib):
    with pytest.raises(sandpaper.UnknownLevel) as info:
        lib.roughness_level("coarsee")
    assert "coarse" in info.value.known
    assert 'did you mean "coarse"' in str(info.value)


def test_an_unknown_percept_is_named_with_the_percepts_that_have_levels(lib):
    # The percepts with levels, read from calibration/levels/'s files.
    percepts = [re.search(r'^percept = "([a-z]+)"', p.read_text(), re.M).group(1)
                for p in sorted(pathlib.Path(lib.calibration_dir, "levels").glob("*.toml"))]
    assert "softness" in percepts and len(percepts) >= 4
    with pytest.raises(sandpaper.UnknownLevel) as info:
        lib.level("bogus", "soft")
    message = str(info.value)
    assert 'unknown percept "bogus"' in message and "known levels: none" not in message
    assert all(p in message for p in percepts), message
    assert info.value.known == []


def test_missing_data_directories_are_all_named():
    with pytest.raises(sandpaper.Error) as info:
        sandpaper.Library(library_dir="/nonexistent/lib", calibration_dir="/nonexistent/cal")
    assert "/nonexistent/lib" in str(info.value) and "/nonexistent/cal" in str(info.value)


def test_explain_is_a_dict_of_what_the_compiler_decided(lib):
    e = lib.compile("corduroy").explain()
    assert e["ok"] is True
    assert e["compiled_max_lateral_force_N"] == pytest.approx(lib.compile("corduroy").compiled_max_lateral_force_N)
    assert e["material"] == "corduroy" and e["provenance"]
    assert {"knowledge", "maps", "felt_at_speed", "terms", "diagnostics"} <= set(e)
    assert all(f["speed_mm_s"] > 0 for f in e["felt_at_speed"])


@pytest.mark.parametrize("speed", [float("nan"), -1.0, float("inf"), 0.0])
def test_a_design_speed_that_is_no_hand_speed_is_refused(lib, speed):
    m = lib.compile("roughness 0.6; grating period 2.5 mm")
    with pytest.raises(ValueError, match="design_speed_m_s must be a finite hand speed above 0 m/s"):
        m.explain(design_speed_m_s=speed)


def test_a_design_speed_adds_its_remedies_at_that_speed(lib):
    e = lib.compile("roughness 0.6; grating period 2.5 mm").explain(design_speed_m_s=0.2)
    design = [r for r in e["felt_remedies"] if r["design_speed"]]
    assert len(design) == 1 and design[0]["speed_mm_s"] == pytest.approx(200.0)
    assert design[0]["felt_peak_N"] > 0
    assert not any(r["design_speed"] for r in lib.compile("roughness 0.6; grating period 2.5 mm").explain()["felt_remedies"])


def test_the_lateral_force_field_is_a_numpy_array_within_the_compiled_maximum(lib):
    m = lib.compile("grating period 2.5 mm hill 50% amplitude 0.8 N")
    field = m.lateral_force_field(window_m=(0.02, 0.02))  # as fine as the ridges need, over 20 mm
    fx, fy = field["fx_N"], field["fy_N"]
    n = fx.shape[0]
    assert fx.shape == (n, n) and fy.shape == (n, n) and field["x_m"].shape == (n,) and n > 200
    magnitude = np.hypot(fx, fy)
    assert magnitude.max() == pytest.approx(0.8, rel=0.05)
    assert magnitude.max() <= m.compiled_max_lateral_force_N * (1 + 1e-6)
    # A grating across x: the force varies along x and not along y.
    assert np.ptp(fx[n // 2, :]) > 1.0 and np.ptp(fx[:, n // 2]) < 1e-9


def test_a_force_field_too_coarse_for_the_grating_is_refused_not_aliased(lib):
    # n = 32 over the default 95 mm patch puts a point every 2.97 mm: the grid would miss the ridges.
    m = lib.compile("grating period 2.5 mm hill 50% amplitude 0.8 N")
    with pytest.raises(ValueError, match=r"use n >= (\d+)") as info:
        m.lateral_force_field(n=32)
    needed = int(re.search(r"use n >= (\d+)", str(info.value)).group(1))
    with pytest.raises(ValueError):
        m.lateral_force_field(n=needed - 1)
    # The n it names is the default, and finds the ridges' peak (within 5 %, the grid's promise).
    field = m.lateral_force_field()
    assert field["fx_N"].shape == (needed, needed)
    assert np.hypot(field["fx_N"], field["fy_N"]).max() == pytest.approx(0.8, rel=0.05)
    # 1.5 mm ridges over 95 mm need more than 4096 points a side: a window of the patch instead.
    fine = lib.compile("grating period 1.5 mm hill 50% amplitude 1.75 N")
    for kwargs in [{"n": 32}, {}]:
        with pytest.raises(ValueError, match="window_m"):
            fine.lateral_force_field(**kwargs)
    window = fine.lateral_force_field(window_m=(0.010, 0.006))
    n = window["fx_N"].shape[0]
    assert window["x_m"][0] == pytest.approx(-0.005 + 0.005 / n) and window["y_m"][-1] == pytest.approx(0.003 - 0.003 / n)
    assert np.hypot(window["fx_N"], window["fy_N"]).max() == pytest.approx(1.75, rel=0.05)
    with pytest.raises(ValueError, match="window_m"):
        fine.lateral_force_field(window_m=(0.0, 0.01))
    # A spring has no ridges: any grid shows it.
    assert lib.compile("spring 200 N/m").lateral_force_field(n=4)["fx_N"].shape == (4, 4)


def test_an_empty_material_is_a_compile_error(lib):
    for text in ["", "   ", "# a comment only"]:
        with pytest.raises(sandpaper.CompileError) as info:
            lib.compile(text)
        assert [d["code"] for d in info.value.diagnostics] == ["E0316"]


def test_a_player_loads_a_name_and_says_what_else_it_takes(lib):
    p = sandpaper.Player.simulated()
    m = p.load("corduroy")
    assert m.name == "corduroy" and m.compiled_max_lateral_force_N == pytest.approx(lib.compile("corduroy").compiled_max_lateral_force_N)
    p.start(rate_hz=1000, duration_s=0.05)
    assert p.wait()["ticks"] == 50
    with pytest.raises(sandpaper.CompileError):
        p.load("corduroyy")
    with pytest.raises(TypeError, match=r"material: sandpaper.Material|material: str"):
        p.load(3)


def test_plays_for_the_duration_and_records_the_trace(lib):
    m = lib.compile("corduroy")
    p = sandpaper.Player.simulated(record_ticks=300)
    p.load(m)
    p.start(rate_hz=1000, duration_s=0.3)
    report = p.wait()
    assert report["ticks"] == 300
    assert report["stop_cause"] == "completed"
    trace = p.trace()
    assert trace.shape == (300, 5)
    assert np.all(np.diff(trace[:, 0]) > 0)  # time runs forward
    forces = np.hypot(trace[:, 3], trace[:, 4])
    assert forces.max() == pytest.approx(report["felt_max_lateral_force_N"])
    assert forces.max() <= m.compiled_max_lateral_force_N * (1 + 1e-9)


def test_the_gil_is_released_while_playing(lib):
    """Python keeps running while another thread is blocked in wait(): if wait() held the GIL, this
    thread could not count until the run was over, and would find it over."""
    p = sandpaper.Player.simulated()
    p.load(lib.compile("corduroy"))
    p.start(rate_hz=1000, duration_s=3.0)
    entered = threading.Event()
    reports = []

    def waiter():
        entered.set()
        reports.append(p.wait())

    t = threading.Thread(target=waiter)
    t.start()
    entered.wait()
    n, end = 0, time.monotonic() + 0.3  # many GIL switch intervals (5 ms): the waiter is in wait() by now
    while time.monotonic() < end:
        n += 1
    still_running = t.is_alive()
    t.join()
    assert n > 1000
    assert still_running, "wait() returned before this thread could count: it held the GIL"
    assert reports[0]["stop_cause"] == "completed"


def test_bad_rates_and_hands_are_value_errors(lib):
    p = sandpaper.Player.simulated()
    p.load(lib.compile("corduroy"))
    with pytest.raises(ValueError):
        p.start(rate_hz=50, duration_s=0.1)
    with pytest.raises(ValueError):
        sandpaper.Player.simulated(hand="zigzag")


def test_usb_opens_a_calibrated_joystick_or_raises_device_error(lib):
    assert sandpaper.Player.simulated().device_calibration == ""
    try:
        p = sandpaper.Player.usb(lib)
    except sandpaper.DeviceError as e:
        assert isinstance(e, sandpaper.Error)
        assert "openffboard-2axis (1209:ffb0)" in str(e)
    else:
        assert p.device_calibration != ""


def test_open_names_a_hidraw_node_that_is_not_there(lib):
    with pytest.raises(sandpaper.DeviceError, match="no hidraw node /nonexistent/hidraw9"):
        sandpaper.Player.open(lib, "hidraw:/nonexistent/hidraw9")
    with pytest.raises(sandpaper.DeviceError, match="the simulated joystick has a player of its own"):
        sandpaper.Player.open(lib, "sim")


def test_uncalibrated_is_for_an_input_event_node_alone(lib):
    # Asked along another path it is refused, not ignored; along evdev it goes as far as the node.
    with pytest.raises(sandpaper.DeviceError, match="--uncalibrated plays an input event node"):
        sandpaper.Player.open(lib, "hidraw", uncalibrated=True)
    with pytest.raises(sandpaper.DeviceError, match="/nonexistent/event99"):
        sandpaper.Player.open(lib, "evdev:/nonexistent/event99", uncalibrated=True)
    with pytest.raises(TypeError):
        sandpaper.Player.open(lib, "evdev", True)  # keyword only: a bare True says nothing at the call
    assert sandpaper.Player.simulated().warning == ""


def test_the_height_field_is_what_the_forces_are_the_gradient_of(lib):
    # A grating: one period, worked back from the force table; k * steepest slope = the peak force.
    g = lib.compile("grating period 2.5 mm hill 50% amplitude 0.8 N").height_field()
    assert g["kind"] == "grating" and g["h_m"].shape == (1, len(g["x_m"]))
    assert g["period_m"] == pytest.approx(0.0025)
    slope = np.abs(np.diff(g["h_m"][0])) / (g["x_m"][1] - g["x_m"][0])
    assert g["k_N"] * slope.max() == pytest.approx(0.8, rel=0.02)
    # A photograph: the image's grid, and -k grad h gives the compiled force field back.
    m = lib.compile("gravel")
    h = m.height_field()
    assert h["kind"] == "height_field" and h["h_m"].shape == (len(h["y_m"]), len(h["x_m"]))
    assert h["h_m"].std() > 0
    dy, dx = np.gradient(h["h_m"], h["y_m"], h["x_m"])
    inner = (slice(8, -8), slice(8, -8))
    assert h["k_N"] * np.hypot(dx, dy)[inner].max() == pytest.approx(m.compiled_max_lateral_force_N, rel=0.05)
    with pytest.raises(sandpaper.Error):
        lib.compile("spring 200 N/m").height_field()


def test_the_simulated_observer_answers_as_the_experiments_do():
    obs = sandpaper.SimulatedObserver("exponent=0.76,noise=0,seed=1", subject="S01")
    a, b = obs.estimate(0.5), obs.estimate(2.0)
    assert b / a == pytest.approx(4 ** 0.76, rel=1e-9)  # noise 0: exactly Stevens' law
    assert obs.choose_interval(1.0, 2.0) == 2
    conf = obs.estimate(3.0, period_m=0.0025, confidence=True)
    assert 0 <= conf <= 100
    with pytest.raises(ValueError):
        sandpaper.SimulatedObserver("exponent=0")
    with pytest.raises(ValueError):
        sandpaper.SimulatedObserver("dimension=softness")  # which exponent?
    soft = sandpaper.SimulatedObserver("dimension=softness,exponent=-0.8,noise=0,seed=1", subject="S01")
    assert soft.estimate(2.0) / soft.estimate(0.5) == pytest.approx(4 ** -0.8, rel=1e-9)  # a stiffer spring: less soft
