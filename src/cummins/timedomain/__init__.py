"""The equation of motion in time.

* :mod:`~cummins.timedomain.simulate`: the linear Cummins equation (Cummins, 1962) with the
  state-space fluid memory, and its reference by direct convolution;
* :mod:`~cummins.timedomain.unified`: the nonlinear 6-DOF model of Smogeli et al. (2004);
* :mod:`~cummins.timedomain.loads`: the environmental and external loads of that model;
* :mod:`~cummins.timedomain.dp`: a dynamic-positioning controller and thrust allocation;
* :mod:`~cummins.timedomain.lfmodel`: the low-frequency manoeuvring model of Ross, Perez &
  Fossen (2006).

The vessel these act on, :class:`cummins.vessel.Vessel`, is shared with the frequency domain.
"""
