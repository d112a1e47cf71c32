"""The convergence study of docs/chatter.md (about 2 minutes):

    OPENBLAS_NUM_THREADS=1 python benchmarks/chatter_convergence.py
"""
import json
import time

import numpy as np

import contactsep
from contactsep import chatter
from contactsep.chatter.event_driven import rigid_stop_from_design

out=[]
def row(model, N, dt, damping='none', d=0.25):
    t0=time.time()
    r=chatter.simulate(contactsep.thesis_design(n_modes=N, d=d), model=model, dt=dt, damping=damping)
    j=r.to_json_dict()
    print(model, damping, d, N, dt, f"{j['first_impulse_lb_s']:.5g} {j['max_lower_gap_in']:.5g} {j['circuit_open_s']:.5g} {j['first_circuit_open_s']} {j['energy_ratio']:.5g} {len(r.circuit_open_intervals)} {time.time()-t0:.1f}s", flush=True)
for N in (4,8,16,32,64):
    row('newton', N, 1e-7)
for N in (4,8,16,32,64):
    row('hertz', N, 2e-8)
for dt in (4e-8, 2e-8, 1e-8):
    row('hertz', 16, dt)
for dt in (1e-6, 2e-7, 1e-7, 5e-8):
    row('newton', 16, dt)
for N in (4,16,32):
    row('hertz', N, 2e-8, 'flores')
for d in (0.125, 0.75):
    for N in (16, 32):
        row('hertz', N, 2e-8, d=d)
        row('newton', N, 1e-7, d=d)
for N in (1,2,4,8,16,32):
    t0=time.time(); r=rigid_stop_from_design(contactsep.thesis_design(n_modes=N), t_end=0.06, max_impacts=200000)
    print('appE', N, r.impact_t[0], r.impulse[0], r.impulse.sum(), len(r.impact_t), np.sum(np.diff(r.rest_intervals,axis=1)) if len(r.rest_intervals) else 0, r.final_energy/r.initial_energy, f'{time.time()-t0:.1f}s', flush=True)
