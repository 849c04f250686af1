"""Thermal correction of the traction (ehl_dataset/model/thermal.py): the flash temperature against Jaeger's and
Blok's published constants, the film solution against its defining equations and limits, the coupled correction in
the steady solver (no effect without sliding or at low speed, more with speed), and the lubricant file's [thermal]
table."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant, lubricant_from_dict
from ehl_dataset.model import thermal
from ehl_dataset.model.thermal import (BLOK_MAX_COEFFICIENT, NEWTON_STEPS, SECANT_ITERATIONS, ThermalProperties,
                                       TemperatureTable, _film_parameter_lockstep, _g, _g_scalar, _secant_film_kernel,
                                       _secant_film_near_kernel, _table_at, blok_denominator, film_centre_rise,
                                       film_parameter, film_shear_stress, film_with_secant_beta, jaeger_operator,
                                       surface_temperature_rise, thermal_couette_traction)
from ehl_dataset.solver import solve_contact
from ehl_dataset.validation import InputError

ATF = load_lubricant("atf")
STEEL = ThermalProperties()
SMOOTH_ISOTHERMAL = Effects(False, False, True, True, "forced")
SMOOTH_THERMAL = Effects(False, False, True, True, "forced", thermal=True)


# ---------------------------------------------------------------------------------------------------------------
# Surfaces: Jaeger's moving band source (high Péclet number) and Blok's flash temperature
# ---------------------------------------------------------------------------------------------------------------
def test_jaeger_operator_is_exact_for_a_uniform_flux():
    """∫_{x0}^{x} (x − ξ)^(−1/2) dξ = 2 √(x − x0): the operator is exact for piecewise-linear flux, also on a
    non-uniform grid."""
    x = np.cumsum(np.r_[0.0, np.random.default_rng(3).uniform(0.2, 1.8, 200)]) * 1e-6
    assert jaeger_operator(x) @ np.ones(x.size) == pytest.approx(2.0 * np.sqrt(x - x[0]), rel=1e-12, abs=1e-15)
    ramp = (x - x[0]) / (x[-1] - x[0])       # ∫ (ξ − x0)(x − ξ)^(−1/2) dξ = (4/3)(x − x0)^(3/2)
    assert jaeger_operator(x) @ ramp == pytest.approx(4.0 / 3.0 * (x - x[0]) ** 1.5 / (x[-1] - x[0]), rel=1e-10,
                                                      abs=1e-18)


def _jaeger_array_formula(x):
    """The operator as dense array arithmetic over all (i, j): on segment j with s0 = √(x_i − ξ_j),
    s1 = √(x_i − ξ_j+1), d = Δ_j/(s0 + s1): weight 2d − i1 to node j and i1 = (2/3) d (2 s0 + s1)/(s0 + s1) to node
    j + 1, for the segments that end at or before x_i."""
    dist = x[:, None] - x[None, :]
    s0 = np.sqrt(np.clip(dist[:, :-1], 0.0, None))
    s1 = np.sqrt(np.clip(dist[:, 1:], 0.0, None))
    active = dist[:, 1:] >= 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.where(active, np.diff(x)[None, :] / (s0 + s1), 0.0)
        i1 = np.where(active, (2.0 / 3.0) * d * (2.0 * s0 + s1) / (s0 + s1), 0.0)
    out = np.zeros((x.size, x.size))
    out[:, :-1] += 2.0 * d - i1
    out[:, 1:] += i1
    return out


def test_jaeger_operator_equals_the_array_formula_on_a_clustered_grid():
    """The compiled operator against the same equations written as array arithmetic, on a grid clustered (100:1)
    around the centre like the solvers' grids."""
    u = np.linspace(-1.0, 1.0, 381)
    x = 4.2e-4 * (u + 0.99 * np.sin(np.pi * u) / np.pi)
    assert np.min(np.diff(x)) < np.max(np.diff(x)) / 50
    reference = _jaeger_array_formula(x)
    op = jaeger_operator(x)
    assert np.all(op[np.triu_indices(x.size, 1)] == 0.0)
    assert np.max(np.abs(op - reference)) <= 1e-13 * np.max(np.abs(reference))
    lower = reference != 0.0
    assert np.max(np.abs(op[lower] - reference[lower]) / np.abs(reference[lower])) <= 1e-13


def test_jaeger_operator_cache_returns_equal_protected_arrays():
    """Repeated grids come from the per-process store: equal values, read-only, so a caller cannot change what the
    next caller gets; arithmetic on the result gives a new array; a grid pushed out of the store is recomputed."""
    x = np.cumsum(np.r_[0.0, np.random.default_rng(5).uniform(0.5, 1.5, 120)]) * 1e-6
    first = jaeger_operator(x)
    expected = _jaeger_array_formula(x)
    again = jaeger_operator(x.copy())
    assert np.array_equal(first, again) and not first.flags.writeable
    with pytest.raises(ValueError):
        first[1, 0] = 0.0
    scaled = jaeger_operator(x) / 2.0
    scaled[:] = -1.0
    copy = np.array(jaeger_operator(x))
    copy[:] = -1.0
    assert np.max(np.abs(jaeger_operator(x) - expected)) <= 1e-13 * np.max(expected)
    for shift in range(1, thermal.JAEGER_CACHE_SIZE + 2):
        jaeger_operator(x + shift * 1e-3)
    assert np.max(np.abs(jaeger_operator(x) - expected)) <= 1e-13 * np.max(expected)
    assert len(thermal._jaeger_cache) <= thermal.JAEGER_CACHE_SIZE
    with pytest.raises(InputError, match="strictly increasing"):
        jaeger_operator(x[::-1])
    with pytest.raises(InputError, match="strictly increasing"):
        jaeger_operator(np.array([0.0]))


def test_uniform_band_source_reproduces_jaegers_constants():
    """A uniform flux q on a band of width 2a passing a surface at speed u (Péclet ≫ 1): maximum rise 1.596 and
    mean rise 1.064 × q √(a κ/u)/k = q √a/(B √u) (Jaeger, J. Proc. R. Soc. N.S.W. 76 (1942) 203, as tabulated by
    Kennedy, "Frictional heating and contact temperatures", Modern Tribology Handbook (2000)). One surface: the
    other has B → 0."""
    a, u, q = 1e-4, 10.0, 1e8
    x = np.linspace(-a, a, 4001)
    single = ThermalProperties()
    rise = surface_temperature_rise(x, np.full(x.size, q), u, 0.0, single)
    scale = q * math.sqrt(a) / (single.effusivity * math.sqrt(u))
    assert rise.max() / scale == pytest.approx(1.596, abs=5e-4)
    assert np.trapezoid(rise, x) / (2 * a) / scale == pytest.approx(1.064, abs=5e-4)


def test_hertzian_flux_reproduces_bloks_flash_temperature():
    """Semi-elliptic flux q0 √(1 − x²/a²) = μ p(x) |u_s|: maximum rise 1.2346 q0 √a/(B1√u1 + B2√u2) (quadrature of
    the Jaeger integral, independent of the discretisation here), i.e. Blok's maximum flash temperature
    1.11 μ w' |u_s| / (√(2a) (B1√u1 + B2√u2)) with w' = π a p_h/2 (Blok 1937; the 1.11 of gear scuffing practice)."""
    a, u1, u2, mu, p_h, u_s = 2e-4, 12.0, 8.0, 0.05, 1e9, 4.0
    x = np.linspace(-a, a, 8001)
    q0 = mu * p_h * u_s
    rise = surface_temperature_rise(x, q0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None)), u1, u2, STEEL)
    sum_b = STEEL.effusivity * (math.sqrt(u1) + math.sqrt(u2))

    def exact(xi):  # ∫_{-1}^{ξ} √(1 − s²)/√(ξ − s) ds / √π with s = ξ − t²
        return quad(lambda t: 2 * math.sqrt(max(1 - (xi - t * t) ** 2, 0.0)), 0, math.sqrt(xi + 1))[0] / math.sqrt(
            math.pi)

    peak = max(exact(v) for v in np.linspace(0.60, 0.70, 201))
    assert peak == pytest.approx(BLOK_MAX_COEFFICIENT, abs=1e-4)
    assert rise.max() * sum_b / (q0 * math.sqrt(a)) == pytest.approx(peak, rel=2e-3)
    w = math.pi * a * p_h / 2
    blok = 1.11 * mu * w * u_s / (math.sqrt(2 * a) * sum_b)
    assert rise.max() == pytest.approx(blok, rel=3e-3)


def test_surface_velocities_are_checked():
    with pytest.raises(InputError, match="surface velocities"):
        surface_temperature_rise(np.array([0.0, 1.0]), np.ones(2), -1.0, 2.0, STEEL)
    assert blok_denominator(4.0, 9.0, STEEL) == pytest.approx(math.sqrt(math.pi) * STEEL.effusivity * 5.0)


# ---------------------------------------------------------------------------------------------------------------
# Film: Eyring fluid, exponential viscosity-temperature law, conduction across the film
# ---------------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("eta, h, beta", [(50.0, 2e-7, 0.05), (1e4, 1e-7, 0.1), (0.05, 5e-7, 0.03),
                                          (3e6, 8e-8, 0.15)])
def test_film_solution_satisfies_its_equations(eta, h, beta):
    """The closed form θ = β(T − T_s) = 2 ln(cosh X/cosh(2Xz/h)) must (1) solve the energy equation
    k θ''/β = −τ γ̇(z) with γ̇ = (τ0/η_s) sinh(τ/τ0) e^θ (checked by central differences at five depths), (2) give the
    prescribed sliding speed u_s = ∫ γ̇ dz and (3) conduct the dissipated heat τ u_s to the walls,
    k θ'(±h/2)/β = ∓τ u_s/2 (both by quadrature): independent of the root-finding."""
    u_s, tau0, k = 5.0, 5e6, 0.14
    tau, x = film_shear_stress(eta, u_s, h, tau0, beta, k)
    tau, x = float(tau), float(x)
    rate = tau0 / eta * math.sinh(tau / tau0)

    def theta(z):
        return 2.0 * (math.log(math.cosh(x)) - math.log(math.cosh(2 * x * z / h)))

    for z in np.linspace(-0.4, 0.4, 5) * h:
        dz = 1e-4 * h
        second = (theta(z + dz) - 2 * theta(z) + theta(z - dz)) / dz**2
        assert k * second / beta == pytest.approx(-tau * rate * math.exp(theta(z)), rel=1e-5)
    speed = quad(lambda z: rate * math.cosh(x) ** 2 / math.cosh(2 * x * z / h) ** 2, -h / 2, h / 2,
                 epsabs=0, epsrel=1e-12)[0]
    assert speed == pytest.approx(u_s, rel=1e-9)
    wall_flux = k / beta * 2.0 * (2 * x / h) * math.tanh(x)        # −k θ'(h/2)/β with θ = 2 ln(cosh X/cosh(2Xz/h))
    assert wall_flux == pytest.approx(tau * u_s / 2, rel=1e-9)


def test_film_limits():
    """β = 0 or u_s = 0: X = 0 and the isothermal Eyring stress exactly; small X: X² → β ΔT_c with Crook's centre
    rise ΔT_c = τ u_s h/(8k) (Crook, Phil. Trans. A 254 (1961) 237), and the stress that of the mean film
    temperature rise τ u_s h/(12 k) (the simplified rule)."""
    eta, h, tau0, k = 30.0, 3e-7, 5e6, 0.14
    iso = tau0 * np.arcsinh(eta * 2.0 / (tau0 * h))
    tau, x = film_shear_stress(eta, 2.0, h, tau0, 0.0, k)
    assert x == 0.0 and tau == iso
    tau, x = film_shear_stress(eta, 0.0, h, tau0, 0.05, k)
    assert x == 0.0 and tau == 0.0
    beta = 1e-4
    tau, x = film_shear_stress(eta, 2.0, h, tau0, beta, k)
    crook = float(tau) * 2.0 * h / (8 * k)
    assert float(x) ** 2 / beta == pytest.approx(crook, rel=1e-3)
    assert float(film_centre_rise(x, beta, tau, 2.0, h, k)) == pytest.approx(crook, rel=1e-3)
    mean_rule = tau0 * np.arcsinh(eta * math.exp(-beta * crook * 8 / 12) * 2.0 / (tau0 * h))
    assert float(tau) == pytest.approx(mean_rule, rel=1e-6)


def test_film_root_is_unique_and_accurate():
    """X tanh X rises and A asinh(S g(X)) falls with X: one root, found to round-off over 11 decades of η."""
    rng = np.random.default_rng(11)
    eta, h, beta = 10 ** rng.uniform(-3, 8, 5000), 10 ** rng.uniform(-8, -6, 5000), rng.uniform(0, 0.2, 5000)
    x = film_parameter(eta, 7.0, h, 5e6, beta, 0.14)
    s, a = eta * 7.0 / (5e6 * h), beta * 7.0 * h * 5e6 / (8 * 0.14)
    residual = x * np.tanh(x) - a * np.arcsinh(s * _g(x))
    assert np.max(np.abs(residual) / (1 + a * np.arcsinh(s))) < 1e-12
    grid = np.linspace(0, 20, 2001)
    assert np.all(np.diff(grid * np.tanh(grid)) > 0) and np.all(np.diff(_g(grid)) < 0)


def _secant_film_lockstep_reference(rises, log_eta, rise, u_s, h, tau0, conductivity):
    """The secant-β film of all nodes in lockstep, every film parameter recomputed by the plain lockstep Newton
    iteration (:func:`_film_parameter_lockstep`) at every secant step: the definition that the compiled kernel,
    which reuses unchanged Newton paths, must reproduce bit for bit."""
    n = rise.size
    log_eta_s, beta = np.empty(n), np.empty(n)
    for i in range(n):
        log_eta_s[i], slope = _table_at(rises, log_eta, i, rise[i])
        beta[i] = max(slope, 0.0)
    eta_s = np.array([math.exp(v) for v in log_eta_s])
    log_eta_s = np.array([math.log(v) for v in eta_s])
    s = eta_s * abs(u_s) / (tau0 * h)
    for _ in range(SECANT_ITERATIONS):
        x = _film_parameter_lockstep(s, beta * abs(u_s) * h * tau0 / (8.0 * conductivity), NEWTON_STEPS)
        done = True
        for i in range(n):
            centre = 2.0 * (x[i] + math.log1p(math.exp(-2.0 * x[i])) - math.log(2.0)) / beta[i] if beta[i] > 0 else 0.0
            secant = beta[i]
            if centre > 1e-6:
                secant = (log_eta_s[i] - math.log(math.exp(_table_at(rises, log_eta, i, rise[i] + centre)[0]))) / centre
            secant = max(secant, 0.0)
            done = done and abs(secant - beta[i]) <= 1e-10 * max(beta[i], 1e-300)
            beta[i] = secant
        if done:
            break
    x = _film_parameter_lockstep(s, beta * abs(u_s) * h * tau0 / (8.0 * conductivity), NEWTON_STEPS)
    tau = np.array([math.copysign(1.0, u_s) * tau0 * math.asinh(s[i] * _g_scalar(x[i])) for i in range(n)])
    return tau, x, beta


def _hot_film_nodes():
    state = ATF.state(363.15)
    p = np.linspace(0.1e9, 1.4e9, 48)
    table = state.temperature_table(p)
    h = np.linspace(1.2e-7, 4e-7, p.size)
    rise = np.linspace(0.0, 70.0, p.size) + 0.37
    return table, h, rise, state.tau0


@pytest.mark.parametrize("u_s", [3.0, 5.0, -12.0])
def test_secant_film_kernel_reproduces_the_plain_lockstep_bit_for_bit(u_s):
    """Reusing the Newton paths of unchanged β (and the secant of unchanged β and X) changes no number: equal to the
    lockstep that recomputes every film parameter at every secant step, and to the array form of
    :func:`film_with_secant_beta` to round-off."""
    table, h, rise, tau0 = _hot_film_nodes()
    rises, log_eta = np.asarray(table.rises, dtype=float), np.ascontiguousarray(table.log_eta)
    kernel = _secant_film_kernel(rises, log_eta, rise, u_s, h, tau0, 0.14, SECANT_ITERATIONS, NEWTON_STEPS)
    reference = _secant_film_lockstep_reference(rises, log_eta, rise, u_s, h, tau0, 0.14)
    for got, want in zip(kernel, reference):
        assert np.array_equal(got, want)
    assert np.max(kernel[1]) > 0.5                 # a hot film: the secant iteration does work
    one_rise = film_with_secant_beta(table, 20.0, u_s, h, tau0, 0.14)              # the array form
    compiled = film_with_secant_beta(table, np.full(h.size, 20.0), u_s, h, tau0, 0.14)
    for got, want in zip(compiled, one_rise):
        assert got == pytest.approx(want, rel=1e-12, abs=0.0)


def test_film_near_a_converged_rise_matches_the_kernel():
    """The film at ΔT_s + 0.01 K started from the β and X converged at ΔT_s (the forward difference of the coupled
    Newton iteration): the kernel's τ to within its secant tolerance; 0 on nodes without liquid."""
    table, h, rise, tau0 = _hot_film_nodes()
    rises, log_eta = np.asarray(table.rises, dtype=float), np.ascontiguousarray(table.log_eta)
    live = np.ones(h.size, dtype=bool)
    live[[0, 7]] = False
    _, x0, beta0 = _secant_film_kernel(rises, log_eta, rise, 5.0, h, tau0, 0.14, SECANT_ITERATIONS, NEWTON_STEPS)
    tau = _secant_film_kernel(rises, log_eta, rise + 0.01, 5.0, h, tau0, 0.14, SECANT_ITERATIONS, NEWTON_STEPS)[0]
    near = _secant_film_near_kernel(rises, log_eta, rise + 0.01, 5.0, h, tau0, 0.14, live, beta0, x0,
                                    SECANT_ITERATIONS, NEWTON_STEPS)
    assert np.all(near[~live] == 0.0)
    assert near[live] == pytest.approx(tau[live], rel=1e-12, abs=0.0)


def test_coupled_correction_without_sliding_or_temperature_dependence():
    """u_s = 0: no heat, no correction. A viscosity that does not depend on temperature (β = 0): the surfaces heat
    up (the flash temperature of the isothermal stress) but τ stays isothermal."""
    x = np.linspace(-2e-4, 2e-4, 301)
    h = np.full(x.size, 2e-7)
    log_eta = np.log(np.full(x.size, 100.0))
    table = TemperatureTable(np.array([0.0, 100.0]), np.vstack([log_eta, log_eta]))
    out = thermal_couette_traction(x, h, table, np.ones(x.size, bool), 5.0, 5.0, 5e6, STEEL)
    assert np.all(out.shear_stress == 0) and np.all(out.surface_rise == 0) and out.converged
    out = thermal_couette_traction(x, h, table, np.ones(x.size, bool), 6.0, 4.0, 5e6, STEEL)
    iso = 5e6 * np.arcsinh(100.0 * 2.0 / (5e6 * 2e-7))
    assert out.converged and out.shear_stress == pytest.approx(np.full(x.size, iso), rel=1e-12)
    expected = surface_temperature_rise(x, np.full(x.size, iso * 2.0), 6.0, 4.0, STEEL)
    assert out.surface_rise == pytest.approx(expected, rel=1e-9)


# ---------------------------------------------------------------------------------------------------------------
# In the steady solver
# ---------------------------------------------------------------------------------------------------------------
def _pair(case, level="fast"):
    iso = solve_contact(case, ATF, level, SMOOTH_ISOTHERMAL)
    hot = solve_contact(case, ATF, level, SMOOTH_THERMAL)
    assert iso.converged and hot.converged, hot.message
    return iso, hot


def test_no_correction_without_sliding():
    """SR = 0: no sliding, no shear heating: μ with the thermal effect equals the isothermal μ exactly."""
    iso, hot = _pair(ContactCase.from_engineering(1.0, 20, 10, 0.0, 90, 0, 0))
    assert hot.mu == iso.mu and hot.extra["thermal"]["max_surface_rise_k"] == 0.0


def test_correction_vanishes_at_low_speed_and_grows_with_speed():
    """1 GPa, 20 mm, SR 0.3, 90 °C (ATF): the flash rise scales as τ u_s √(a/u_r) and the film rise as τ u_s h/k,
    both → 0 with the speed; μ_thermal/μ_isothermal falls monotonically as u_r rises 0.001 → 20 m/s, from within
    0.25 % of 1 at 1 mm/s, and the reduction shrinks at least as fast as √u_r towards low speed."""
    ratios = []
    for u_r in (0.001, 0.01, 0.1, 1.0, 5.0, 10.0, 20.0):
        iso, hot = _pair(ContactCase.from_engineering(1.0, 20, u_r, 0.3, 90, 0, 0))
        ratios.append(hot.mu / iso.mu)
    assert ratios[0] > 0.9975
    assert (1 - ratios[0]) / (1 - ratios[1]) < 1 / math.sqrt(10)
    assert all(later < earlier for earlier, later in zip(ratios, ratios[1:]))
    assert ratios[-1] < 0.8


def test_thermal_result_records_its_temperatures_and_isothermal_mu():
    iso, hot = _pair(ContactCase.from_engineering(1.0, 20, 10, 0.3, 90, 0, 0))
    record = hot.extra["thermal"]
    assert record["mu_isothermal"] == pytest.approx(iso.mu, rel=1e-12)
    assert record["converged"] and record["max_surface_rise_k"] > 0 and record["max_film_centre_rise_k"] > 0
    assert hot.effects["thermal"] and not iso.effects["thermal"]
    assert hot.extra["mu_poiseuille"] == pytest.approx(iso.extra["mu_poiseuille"], rel=1e-12)  # film isothermal
    assert hot.h_min == iso.h_min


def test_rough_solvers_record_that_they_ran_isothermal():
    """The transient solver has no thermal model: a plan asking for it is recorded off, with the reason."""
    case = ContactCase.from_engineering(1.0, 20, 5, 0.3, 90, 0.4, 0.4)
    plan = Effects(True, True, True, True, "forced", {"decisions": {}}, thermal=True)
    from ehl_dataset.solvers.problem import _isothermal

    ran = _isothermal(plan, "transient")
    assert not ran.thermal and "no thermal model" in ran.reasons["decisions"]["thermal"]
    assert case.s_c > 0


# ---------------------------------------------------------------------------------------------------------------
# Lubricant data
# ---------------------------------------------------------------------------------------------------------------
def _definition(**thermal):
    import tomllib

    from ehl_dataset.data_files import resolve_named_file

    data = tomllib.loads(resolve_named_file("lubricants", "gear_oil_75w90", ".toml").read_text())
    if thermal:
        data["thermal"] = thermal
    return data


def test_temperature_coefficient_from_the_lubricant_laws():
    """β(p) = −∂ln η/∂T: for a Barus oil with one α the pressure term does not depend on T, so β is the Walther
    slope at every pressure; the ATF's α1 falls log-linearly from 1.5e-8 (40 °C) to 1.1e-8 1/Pa (100 °C,
    data/lubricants/atf.toml), so below p_a its β grows by −p dα1/dT = p α1 ln(1.5/1.1)/60 K."""
    oil = load_lubricant("gear_oil_75w90").state(373.15)
    betas = oil.viscosity_temperature_coefficient(np.array([0.0, 1e9]))
    assert betas[1] == pytest.approx(betas[0], rel=1e-12) and 0.01 < betas[0] < 0.05
    atf = ATF.state(343.15)
    p = 0.3e9
    growth = atf.viscosity_temperature_coefficient(p) - atf.viscosity_temperature_coefficient(0.0)
    assert growth == pytest.approx(p * atf.alpha1 * math.log(1.5 / 1.1) / 60.0, rel=1e-4)


def test_thermal_table_overrides_and_needs_a_source():
    lub = lubricant_from_dict({**_definition(oil_conductivity_w_mk=0.2, viscosity_temperature_coefficient_per_k=0.04),
                               "sources": {"thermal": "test values"}})
    assert lub.thermal.oil_conductivity == 0.2 and lub.thermal.source == "test values"
    state = lub.state(373.15)
    assert state.viscosity_temperature_coefficient(5e8) == 0.04
    table = state.temperature_table(np.array([5e8]), np.array([0.0, 10.0]))
    assert table.log_eta[1, 0] - table.log_eta[0, 0] == pytest.approx(-0.4, rel=1e-12)
    assert load_lubricant("atf").thermal == ThermalProperties()
    with pytest.raises(InputError, match="sources.thermal"):
        lubricant_from_dict(_definition(oil_conductivity_w_mk=0.2))
    with pytest.raises(InputError, match="thermal.oil_conductivity_w_mk"):
        lubricant_from_dict({**_definition(oil_conductivity_w_mk=-1.0), "sources": {"thermal": "x"}})
    with pytest.raises(InputError, match="thermal.conductivity"):
        lubricant_from_dict({**_definition(conductivity=0.1), "sources": {"thermal": "x"}})
