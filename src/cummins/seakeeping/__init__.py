"""Seakeeping in the frequency domain: the waves, the forces they exert, the motions.

* :mod:`~cummins.seakeeping.spectra`: sea-state spectra (JONSWAP, Pierson–Moskowitz,
  Torsethaugen);
* :mod:`~cummins.seakeeping.waves`: sea states: spreading, wave components, regular waves,
  the dispersion relation (the spectra re-exported);
* :mod:`~cummins.seakeeping.excitation`: first-order wave forces at any frequency and heading;
* :mod:`~cummins.seakeeping.headings`: the headings of the excitation data: coverage,
  port/starboard mirroring, interpolation weights;
* :mod:`~cummins.seakeeping.frequency_domain`: motion RAOs and response spectra, the
  reference a time-domain model is checked against.
"""
