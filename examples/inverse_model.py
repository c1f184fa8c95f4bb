"""Inverse model: which current makes the damper produce a target force (Fig. 2.10 case)."""

import numpy as np

from mrsuspension.dampers import KnownPeak, WangSymmetric

t = np.linspace(0.0, 2.0, 2001)
w = 3.0 * np.pi
current = 0.25 + 0.2 * np.sin(w * t)  # A
x, v, a = 0.025 * np.sin(w * t), 0.025 * w * np.cos(w * t), -0.025 * w**2 * np.sin(w * t)

damper = WangSymmetric(vh_variant="2.13", estimator=KnownPeak(0.025 * w))
force = damper.force(x, v, a, current)
recovered = damper.inverse_current(force, v, a, stroke=x)
print(f"largest current error: {np.max(np.abs(recovered - current)):.1e} A")
print(f"current for 1 kN at 0.1 m/s: {float(damper.inverse_current(1000.0, 0.1, -1.0)):.4f} A")
