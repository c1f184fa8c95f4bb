"""Current shaping: the ADFG algorithm makes the symmetric damper asymmetric (Fig. 2.8)."""

from mrsuspension.characterisation import harmonic_loop
from mrsuspension.dampers import WangSymmetric
from mrsuspension.shaping import adfg_multiplier

damper = WangSymmetric()


def adfg(velocity, peak_velocity, control_current):
    """i_d = M_p(p=0, xi=2) i_c: no current in compression, full current in rebound."""
    return adfg_multiplier(velocity, peak_velocity, p=0.0, xi=2.0) * control_current


for current in (0.1, 0.2, 0.3):
    loop = harmonic_loop(damper, 1.5, 0.0125, current, current_shaping=adfg)
    ratio = loop.max_rebound_force / loop.max_compression_force
    print(f"i_c = {current:.1f} A: rebound/compression force ratio gamma = {ratio:.2f}")
