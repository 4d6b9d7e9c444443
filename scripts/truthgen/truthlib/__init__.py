"""truthgen: measured-style data from hand-written truth models, independent of mbgen.

Modules: assembly (quadratic-form rigid-body assembler), models (mdof2, spindle, frame3), cases (truth variants),
response (FRF by direct solve, exact zero-order-hold simulation, sensor filters and delays), chain (errors of the
measurement chain: gains, polarity, swapped cables, units, FRF forms), datafiles (CSV and truth JSON), effects
(how far the nominal model is from each truth: the size of each hidden effect).
"""
