"""Seakeeping in the frequency domain: the waves, the forces they exert, the motions.

* :mod:`~cummins.seakeeping.waves`: sea states (JONSWAP, Pierson–Moskowitz, Torsethaugen),
  spreading, wave components, regular waves, the dispersion relation;
* :mod:`~cummins.seakeeping.excitation`: first-order wave forces at any frequency and heading;
* :mod:`~cummins.seakeeping.frequency_domain`: motion RAOs and response spectra, the
  reference a time-domain model is checked against.
"""
