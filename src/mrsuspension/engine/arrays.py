"""What the compiled step takes: :class:`KernelArrays` (named).

The entry points of :mod:`mrsuspension.engine.kernel` take their arrays positionally
(numba compiles over arrays and scalars, not Python objects). :class:`KernelArrays` gives
them domain names and is the one place they are put in the kernels' order
(:meth:`KernelArrays.args`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["KernelArrays"]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class KernelArrays:
    """The compiled step's parameters and states of one simulation, by name.

    Built by :meth:`Simulation.kernel_arrays <mrsuspension.engine.Simulation.kernel_arrays>`.
    The states (``damper_state``, the estimators' states and ``memory``) are changed in
    place by the kernels; the rest is read only.

    ==============================  ======  =================================================
    field                           kernel  contents (model-reference symbols)
    ==============================  ======  =================================================
    ``vehicle``                     ``vp``  ``m_s, m_u, k_s, k_t, c_t, c_sky, g, dx_u``
                                            (:mod:`mrsuspension.vehicle.kernel` ``V_*``)
    ``force_source``                ``fk``  where ``F_d`` comes from: the damper model, an
                                            ideal damper (3.12)/(3.13) or a measured force
                                            (:mod:`mrsuspension.control.kernel` ``F_*``)
    ``damper_kind``                 ``dk``  damper model code (:mod:`~mrsuspension.dampers.kernels`)
    ``damper_params``               ``dp``  the damper model's parameters (Table 2.2/2.3
                                            for the dissertation's model; layout per model)
    ``damper_state``                ``ds``  the damper's latched internals (``v_m``,
                                            ``sgn(a_d)``, ``i``, ...) and internal states
    ``damper_estimator_kind``       ``dek`` the damper's peak-velocity estimator code
    ``damper_estimator_params``     ``dep`` its parameters (window, clamp of ``v_m``)
    ``damper_estimator_state``      ``des`` its buffer
    ``controller_kind``             ``ck``  control law code (:mod:`mrsuspension.control.kernel`
                                            ``C_*``)
    ``controller_params``           ``cp``  ``i_H, k_c, n, policy, p, xi, p_c, xi_c, i_max,
                                            lambda, eps, phi, beta, m_s0, c_s, c_0``
                                            (``P_*``)
    ``controller_estimator_kind``   ``cek`` the controller's peak-velocity estimator code
                                            (``EST_SHARED``: the damper's own ``v_m``)
    ``controller_estimator_params`` ``cep`` its parameters
    ``controller_estimator_state``  ``ces`` its buffer
    ``memory``                      ``mem`` carried between steps and the step's outputs:
                                            ``a_d``, ``i_d``, ``i_z``, ``z_c``, ``F*``,
                                            ``v_m``, ... (:mod:`mrsuspension.engine.kernel`
                                            ``M_*``)
    ==============================  ======  =================================================

    Examples
    --------
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> arrays = Simulation(Harmonic(1.0, 0.01)).kernel_arrays(1e-4)
    >>> float(arrays.vehicle[0]), len(arrays.args())
    (563.0, 14)
    """

    vehicle: FloatArray
    force_source: int
    damper_kind: int
    damper_params: FloatArray
    damper_state: FloatArray
    damper_estimator_kind: int
    damper_estimator_params: FloatArray
    damper_estimator_state: FloatArray
    controller_kind: int
    controller_params: FloatArray
    controller_estimator_kind: int
    controller_estimator_params: FloatArray
    controller_estimator_state: FloatArray
    memory: FloatArray

    def args(self) -> tuple[Any, ...]:
        """The arrays in the kernels' order (``vp, fk, dk, ..., ces, mem``).

        :func:`~mrsuspension.engine.kernel.start`, :func:`~mrsuspension.engine.kernel.step`
        and :func:`~mrsuspension.engine.kernel.run` take them as one block.

        Examples
        --------
        >>> from mrsuspension.engine import Simulation
        >>> from mrsuspension.excitation import Harmonic
        >>> a = Simulation(Harmonic(1.0, 0.01)).kernel_arrays(1e-4)
        >>> a.args()[0] is a.vehicle and a.args()[-1] is a.memory
        True
        """
        return (
            self.vehicle,
            self.force_source,
            self.damper_kind,
            self.damper_params,
            self.damper_state,
            self.damper_estimator_kind,
            self.damper_estimator_params,
            self.damper_estimator_state,
            self.controller_kind,
            self.controller_params,
            self.controller_estimator_kind,
            self.controller_estimator_params,
            self.controller_estimator_state,
            self.memory,
        )

    def replace(self, **changes: Any) -> KernelArrays:
        """A copy with some fields replaced (the other arrays are shared, not copied).

        Examples
        --------
        >>> from mrsuspension.control.kernel import F_EXTERNAL
        >>> from mrsuspension.engine import Simulation
        >>> from mrsuspension.excitation import Harmonic
        >>> a = Simulation(Harmonic(1.0, 0.01)).kernel_arrays(1e-4)
        >>> a.replace(force_source=F_EXTERNAL).force_source == F_EXTERNAL
        True
        """
        return dataclasses.replace(self, **changes)
