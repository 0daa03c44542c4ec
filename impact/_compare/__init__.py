"""Comparisons with other codes: the same scene run by a discrete-element code beside `impact.sweep`.

`impact compare lammps` maps a scene onto LAMMPS's granular contact models (`lammps_model`),
runs every speed of a sweep as one batch of particles through the `lammps` Python module
(`lammps_batch`), twice (dt and dt/2), runs the same speeds through `impact.sweep` and tabulates
both (`comparison`). The layer sits between the command line and the benchmarks; its figure is
drawn in `_plots.compare`.
"""
