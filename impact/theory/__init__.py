"""Closed-form results of the JKR/MDR theory of adhesive normal contact and impact.

Plain functions of SI parameters written with ``jax.numpy``: they take scalars or arrays,
broadcast, and work under ``jit``/``vmap``/``grad`` (float64 when x64 is enabled). Equation
numbers refer to the chapter "Normal contact with adhesion" of Popov, Heß & Willert (2019),
*Handbook of Contact Mechanics: Exact Solutions of Axisymmetric Contact Problems* (Springer).

Conventions: indentation d > 0 pressed in, force F > 0 compressive, F < 0 adhesive;
``work_of_adhesion`` is the Dupré work Δγ [J/m²] (not a surface energy γ); ``E_star`` is the
effective modulus `E*` [Pa]; ``xi`` selects the stability criterion (3.35): 3 force control,
1 displacement control. A free body separates at the displacement-controlled point (ξ = 1).
Critical values are returned as a tuple ``(a_c [m], d_c [m], F_c [N])``.

MDR profiles used here (3.24): paraboloid f = r²/(2R) → g = x²/R; power law f = c rⁿ →
g = κ(n) c |x|ⁿ; cone → g = (π/2) tanθ |x|; sphere → g = x artanh(x/R); ellipsoid
f = R(1 − √(1 − k²r²)) → g = kR x artanh(kx) (a sphere of radius 1/k scaled by kR).

Misprints found in the chapter (the code uses the corrected forms):

- (3.57): d(a) must read `kR·a·artanh(ka) − √(2πaΔγ/E*)`; the factor kR is missing (the F_N
  line and the critical values (3.54)–(3.56) with `β = ξ√(πΔγ/(2E*kR²))` are correct).
- (3.56): √a must read √α. Its F_c also cancels to O(α³) for a_c ≪ R, losing about
  2 log₁₀(R/a_c) digits; ``ellipsoid_critical`` uses an equivalent cancellation-free form.
- (3.87): the truncated cone's equation has roots for β ≥ 2.1219 (min of (φ + cot φ)/√cos φ), not
  2.125; (3.110): the capped cone's for β ≥ 1.7967, not 1.795; (3.123) `β0 ≈ 2.2 + 3.2 R1/R*` is a
  fit (β0 = 2 at `R1/R* = 0`): ``*_threshold`` compute the exact minima. Between β = 2 and β0 the
  capped paraboloid loses contact at the edge of its cap (a = b, where the flank's slope jumps),
  not at the JKR state of R1 (whose radius then lies beyond b).
- Where a profile has two critical states (a flat tip or cap and the flank: §3.5.8–3.5.12) the
  contact is lost at the deeper one, not always at the flank's second root: a displacement-
  controlled contact snaps from the flank's minimum of d(a) onto the inner branch and survives
  while that branch reaches lower d (ξ = 1), a force-controlled one while it reaches a lower
  force (ξ = 3). ``*_pull_off`` pick the state that ends the contact; ``*_critical`` give the
  chapter's roots.
- §3.8.4, large Tabor parameter: (3.183) prints the ε₁^(3/2) coefficient of F̃_N as 23/6 (it is
  11/6: κ² arccos(1/κ) + √(κ² − 1) = √2(2ε₁^(1/2) + (11/6)ε₁^(3/2) + …)), and its first line drops
  −(4/9)ãΛε₁², of the same order as the term it keeps (so (3.184) lacks +1/(12ã²Λ⁴)). With both,
  F̃_N = ã³ − 2ã^(3/2) + (ã² − (13/12)ã^(1/2))/Λ² (the printed d̃ of (3.185) is right), and the
  pull-off (3.189) is F̃_A = 1 + 1/(12Λ²), not 1 + 11/(12Λ²); in (3.190) 11/24 becomes 1/24.
  ``maugis_pull_off`` (the exact minimum of (3.171)) confirms 1/12, remainder ≈ −0.0515/Λ⁴.
  (3.186)–(3.187), built on 23/12, inherit the error; (3.188)'s derivative is garbled besides
  (its root follows from (3.187)).

(3.51) and (3.82) follow exactly from the energy balance (see ``power_law_energy_loss``), and
(3.82) reduces to (3.51) at n = 2, c = 1/(2R).

A viscoelastic half-space (a Prony series, ``prony_relaxation_modulus``): Lee & Radok's force of
a paraboloid pressed at a constant rate and held (``lee_radok_force``), Ting's while it is
unloaded (``ting_force``), jax.numpy closed forms up to one bisection.

The Maugis–Dugdale functions (§3.6–3.8, from ``tabor_parameter`` on) use numpy/scipy (hypergeometric
function, scalar minimization) and compute in float64 whatever the jax setting. The
Greenwood–Johnson double-Hertz functions (§3.9, ``double_hertz_*``) are jax.numpy closed forms
(jit/vmap/grad-ready); their equivalent Tabor parameter maps k onto the Maugis–Dugdale Λ.
"""

from ..profiles import kappa as kappa
from ._adhesive_plastic import adhesive_plastic_dent as adhesive_plastic_dent
from ._adhesive_plastic import adhesive_plastic_losses as adhesive_plastic_losses
from ._adhesive_plastic import adhesive_plastic_max_indentation as adhesive_plastic_max_indentation
from ._adhesive_plastic import adhesive_plastic_max_radius as adhesive_plastic_max_radius
from ._adhesive_plastic import adhesive_plastic_restitution as adhesive_plastic_restitution
from ._adhesive_plastic import adhesive_plastic_sticking_velocity as adhesive_plastic_sticking_velocity
from ._adhesive_plastic import adhesive_plastic_touch_pressure as adhesive_plastic_touch_pressure
from ._adhesive_plastic import adhesive_plastic_yield_radius as adhesive_plastic_yield_radius
from ._adhesive_plastic import adhesive_plastic_yield_velocity as adhesive_plastic_yield_velocity
from ._compound import capped_cone_beta as capped_cone_beta
from ._compound import capped_cone_critical as capped_cone_critical
from ._compound import capped_cone_pull_off as capped_cone_pull_off
from ._compound import capped_cone_threshold as capped_cone_threshold
from ._compound import capped_flat_punch_critical as capped_flat_punch_critical
from ._compound import (
    capped_flat_punch_normalized_force as capped_flat_punch_normalized_force,
)
from ._compound import capped_flat_punch_thresholds as capped_flat_punch_thresholds
from ._compound import capped_paraboloid_beta as capped_paraboloid_beta
from ._compound import capped_paraboloid_critical as capped_paraboloid_critical
from ._compound import capped_paraboloid_pull_off as capped_paraboloid_pull_off
from ._compound import capped_paraboloid_threshold as capped_paraboloid_threshold
from ._compound import rounded_flat_punch_beta as rounded_flat_punch_beta
from ._compound import rounded_flat_punch_critical as rounded_flat_punch_critical
from ._compound import truncated_cone_beta as truncated_cone_beta
from ._compound import truncated_cone_critical as truncated_cone_critical
from ._compound import truncated_cone_pull_off as truncated_cone_pull_off
from ._compound import truncated_cone_threshold as truncated_cone_threshold
from ._compound import truncated_paraboloid_beta as truncated_paraboloid_beta
from ._compound import truncated_paraboloid_critical as truncated_paraboloid_critical
from ._compound import truncated_paraboloid_pull_off as truncated_paraboloid_pull_off
from ._compound import truncated_paraboloid_threshold as truncated_paraboloid_threshold
from ._critical import cone_critical as cone_critical
from ._critical import ellipsoid_critical as ellipsoid_critical
from ._critical import flat_punch_critical as flat_punch_critical
from ._critical import paraboloid_critical as paraboloid_critical
from ._critical import paraboloid_jump_in as paraboloid_jump_in
from ._critical import power_law_critical as power_law_critical
from ._critical import power_law_half_threshold as power_law_half_threshold
from ._critical import power_law_jump_in as power_law_jump_in
from ._critical import sphere_critical as sphere_critical
from ._damping import dashpot_contact_time as dashpot_contact_time
from ._damping import dashpot_restitution as dashpot_restitution
from ._damping import viscoelastic_beta as viscoelastic_beta
from ._damping import viscoelastic_restitution_first_order as viscoelastic_restitution_first_order
from ._double_hertz import double_hertz_adhesive_stress as double_hertz_adhesive_stress
from ._double_hertz import double_hertz_factor as double_hertz_factor
from ._double_hertz import double_hertz_force as double_hertz_force
from ._double_hertz import double_hertz_indentation as double_hertz_indentation
from ._double_hertz import double_hertz_onset as double_hertz_onset
from ._double_hertz import double_hertz_outer_radius as double_hertz_outer_radius
from ._double_hertz import double_hertz_pull_off as double_hertz_pull_off
from ._double_hertz import double_hertz_range as double_hertz_range
from ._double_hertz import double_hertz_tabor_parameter as double_hertz_tabor_parameter
from ._friction import cattaneo_mindlin_displacement as cattaneo_mindlin_displacement
from ._friction import cattaneo_mindlin_force as cattaneo_mindlin_force
from ._friction import cattaneo_mindlin_stick_radius as cattaneo_mindlin_stick_radius
from ._friction import effective_shear_modulus as effective_shear_modulus
from ._friction import full_slip_displacement as full_slip_displacement
from ._friction import gross_sliding_tangent as gross_sliding_tangent
from ._friction import masing_program_force as masing_program_force
from ._friction import mindlin_deresiewicz_force as mindlin_deresiewicz_force
from ._friction import sliding_impact as sliding_impact
from ._impact import attach_on_touch_energy_loss as attach_on_touch_energy_loss
from ._impact import attach_on_touch_restitution as attach_on_touch_restitution
from ._impact import force_release_energy_loss as force_release_energy_loss
from ._impact import hertz_contact_time as hertz_contact_time
from ._impact import hertz_max_force as hertz_max_force
from ._impact import hertz_max_indentation as hertz_max_indentation
from ._impact import power_law_beta as power_law_beta
from ._impact import power_law_energy_loss as power_law_energy_loss
from ._impact import power_law_hertz_contact_time as power_law_hertz_contact_time
from ._impact import power_law_hertz_max_force as power_law_hertz_max_force
from ._impact import power_law_hertz_max_indentation as power_law_hertz_max_indentation
from ._impact import power_law_restitution as power_law_restitution
from ._impact import power_law_sticking_velocity as power_law_sticking_velocity
from ._impact import thornton_ning_beta as thornton_ning_beta
from ._impact import thornton_ning_energy_loss as thornton_ning_energy_loss
from ._impact import thornton_ning_max_force as thornton_ning_max_force
from ._impact import thornton_ning_restitution as thornton_ning_restitution
from ._impact import thornton_ning_sticking_velocity as thornton_ning_sticking_velocity
from ._jkr import jkr_force as jkr_force
from ._jkr import jkr_indentation as jkr_indentation
from ._jkr import jkr_normalized_force as jkr_normalized_force
from ._jkr import jkr_normalized_indentation as jkr_normalized_indentation
from ._jkr import power_law_force as power_law_force
from ._jkr import power_law_indentation as power_law_indentation
from ._jkr import power_law_normalized_force as power_law_normalized_force
from ._jkr import power_law_normalized_indentation as power_law_normalized_indentation
from ._maugis import bradley_pull_off as bradley_pull_off
from ._maugis import dmt_pull_off as dmt_pull_off
from ._maugis import dmt_zone_radius as dmt_zone_radius
from ._maugis import dugdale_zone_width as dugdale_zone_width
from ._maugis import maugis_adhesive_stress as maugis_adhesive_stress
from ._maugis import maugis_critical_state as maugis_critical_state
from ._maugis import maugis_junction_zone_radius as maugis_junction_zone_radius
from ._maugis import maugis_paraboloid as maugis_paraboloid
from ._maugis import maugis_paraboloid_noncontact as maugis_paraboloid_noncontact
from ._maugis import maugis_paraboloid_state as maugis_paraboloid_state
from ._maugis import maugis_power_law_state as maugis_power_law_state
from ._maugis import maugis_pull_off as maugis_pull_off
from ._maugis import maugis_pull_off_force as maugis_pull_off_force
from ._maugis import (
    maugis_pull_off_force_large_tabor as maugis_pull_off_force_large_tabor,
)
from ._maugis import maugis_pull_off_large_tabor as maugis_pull_off_large_tabor
from ._maugis import maugis_range as maugis_range
from ._maugis import power_law_dmt_pull_off as power_law_dmt_pull_off
from ._maugis import tabor_criterion as tabor_criterion
from ._maugis import tabor_parameter as tabor_parameter
from ._plastic import thornton_loading_work as thornton_loading_work
from ._plastic import thornton_max_indentation as thornton_max_indentation
from ._plastic import thornton_restitution as thornton_restitution
from ._plastic import thornton_yield_force as thornton_yield_force
from ._plastic import thornton_yield_indentation as thornton_yield_indentation
from ._plastic import thornton_yield_velocity as thornton_yield_velocity
from ._special import constant_stress_profile as constant_stress_profile
from ._special import constant_stress_pull_off as constant_stress_pull_off
from ._special import constant_stress_uniform_state as constant_stress_uniform_state
from ._special import kendall_to_optimal_ratio as kendall_to_optimal_ratio
from ._special import wavy_paraboloid_force as wavy_paraboloid_force
from ._special import wavy_paraboloid_indentation as wavy_paraboloid_indentation
from ._special import wavy_paraboloid_normalized as wavy_paraboloid_normalized
from ._viscoelastic import lee_radok_force as lee_radok_force
from ._viscoelastic import lee_radok_kernel as lee_radok_kernel
from ._viscoelastic import prony_relaxation_modulus as prony_relaxation_modulus
from ._viscoelastic import ting_contact_time as ting_contact_time
from ._viscoelastic import ting_force as ting_force

__all__ = [
    "adhesive_plastic_dent",
    "adhesive_plastic_losses",
    "adhesive_plastic_max_indentation",
    "adhesive_plastic_max_radius",
    "adhesive_plastic_restitution",
    "adhesive_plastic_sticking_velocity",
    "adhesive_plastic_touch_pressure",
    "adhesive_plastic_yield_radius",
    "adhesive_plastic_yield_velocity",
    "kappa",
    "power_law_indentation",
    "power_law_force",
    "power_law_normalized_indentation",
    "power_law_normalized_force",
    "jkr_indentation",
    "jkr_force",
    "jkr_normalized_indentation",
    "jkr_normalized_force",
    "flat_punch_critical",
    "cone_critical",
    "power_law_critical",
    "paraboloid_critical",
    "ellipsoid_critical",
    "sphere_critical",
    "power_law_jump_in",
    "paraboloid_jump_in",
    "power_law_energy_loss",
    "power_law_beta",
    "power_law_restitution",
    "power_law_sticking_velocity",
    "thornton_ning_energy_loss",
    "thornton_ning_beta",
    "thornton_ning_restitution",
    "thornton_ning_max_force",
    "thornton_ning_sticking_velocity",
    "force_release_energy_loss",
    "attach_on_touch_energy_loss",
    "attach_on_touch_restitution",
    "power_law_hertz_max_indentation",
    "power_law_hertz_max_force",
    "power_law_hertz_contact_time",
    "hertz_max_indentation",
    "hertz_max_force",
    "hertz_contact_time",
    "truncated_cone_beta",
    "truncated_cone_threshold",
    "truncated_cone_critical",
    "truncated_cone_pull_off",
    "truncated_paraboloid_beta",
    "truncated_paraboloid_threshold",
    "truncated_paraboloid_critical",
    "truncated_paraboloid_pull_off",
    "capped_flat_punch_thresholds",
    "capped_flat_punch_critical",
    "capped_flat_punch_normalized_force",
    "capped_cone_beta",
    "capped_cone_threshold",
    "capped_cone_critical",
    "capped_cone_pull_off",
    "capped_paraboloid_beta",
    "capped_paraboloid_threshold",
    "capped_paraboloid_critical",
    "capped_paraboloid_pull_off",
    "rounded_flat_punch_beta",
    "rounded_flat_punch_critical",
    "wavy_paraboloid_indentation",
    "wavy_paraboloid_force",
    "wavy_paraboloid_normalized",
    "constant_stress_profile",
    "constant_stress_uniform_state",
    "constant_stress_pull_off",
    "kendall_to_optimal_ratio",
    "power_law_half_threshold",
    "tabor_parameter",
    "maugis_adhesive_stress",
    "maugis_range",
    "tabor_criterion",
    "bradley_pull_off",
    "dmt_pull_off",
    "dmt_zone_radius",
    "dugdale_zone_width",
    "power_law_dmt_pull_off",
    "maugis_paraboloid_state",
    "maugis_power_law_state",
    "maugis_paraboloid",
    "maugis_junction_zone_radius",
    "maugis_paraboloid_noncontact",
    "maugis_pull_off",
    "maugis_critical_state",
    "maugis_pull_off_force",
    "maugis_pull_off_large_tabor",
    "maugis_pull_off_force_large_tabor",
    "double_hertz_outer_radius",
    "double_hertz_force",
    "double_hertz_indentation",
    "double_hertz_pull_off",
    "double_hertz_onset",
    "double_hertz_adhesive_stress",
    "double_hertz_range",
    "double_hertz_tabor_parameter",
    "double_hertz_factor",
    "thornton_yield_indentation",
    "thornton_yield_force",
    "thornton_yield_velocity",
    "thornton_restitution",
    "thornton_loading_work",
    "thornton_max_indentation",
    "prony_relaxation_modulus",
    "lee_radok_kernel",
    "lee_radok_force",
    "ting_contact_time",
    "ting_force",
    "effective_shear_modulus",
    "full_slip_displacement",
    "cattaneo_mindlin_force",
    "cattaneo_mindlin_displacement",
    "cattaneo_mindlin_stick_radius",
    "mindlin_deresiewicz_force",
    "masing_program_force",
    "gross_sliding_tangent",
    "sliding_impact",
]
