"""F-v loops of the dissertation's model at several currents, saved as a PNG.

Run: ``python examples/damper_loops.py`` (writes ``damper_loops.png``).
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from mrsuspension.characterisation import harmonic_loop
from mrsuspension.dampers import WangSymmetric

damper = WangSymmetric("wang-symmetric-low")
fig, ax = plt.subplots()
for current in (0.0, 0.1, 0.2, 0.3, 0.4):
    loop = harmonic_loop(damper, frequency=1.5, amplitude=0.0125, current=current)
    ax.plot(loop.velocity, loop.force, label=f"{current:g} A")
    print(
        f"{current:.1f} A: peak force {loop.max_rebound_force:7.1f} N, "
        f"{loop.energy_per_cycle():6.1f} J per cycle"
    )
ax.set_xlabel("velocity [m/s]")
ax.set_ylabel("force [N]")
ax.legend()
fig.savefig("damper_loops.png", dpi=100)
print("wrote damper_loops.png")
