"""Reference counts stay put across many calls: no leaked references to inputs or results."""

import gc
import sys

import numpy as np

import vibrissa


def test_inputs_are_not_leaked(small_whisker, peg_track):
    target = np.array([0.02, 0.004, 0.0])
    options = vibrissa.SolveOptions()
    before = (sys.getrefcount(small_whisker), sys.getrefcount(target), sys.getrefcount(options),
              sys.getrefcount(peg_track))
    for _ in range(300):
        s = vibrissa.solve_point(small_whisker, target, options=options, warm=None)
        vibrissa.solve_point_batch(small_whisker, peg_track, options=options)
        vibrissa.solve_point_batch([small_whisker, small_whisker], peg_track)
    del s
    after = (sys.getrefcount(small_whisker), sys.getrefcount(target), sys.getrefcount(options),
             sys.getrefcount(peg_track))
    assert before == after


def test_results_are_owned_once(small_whisker, peg_track):
    s = vibrissa.solve_point(small_whisker, [0.02, 0.004, 0.0])
    assert sys.getrefcount(s) == 2
    cp = s.contact_point_W
    assert sys.getrefcount(cp) == 2
    batch = vibrissa.solve_point_batch(small_whisker, peg_track)
    refs = sys.getrefcount(batch.force_W)  # outside `assert`: pytest's rewriting would hold one more
    assert refs == 2  # held by the result only (+1 for the call)


def test_no_growth_in_live_objects(small_whisker, peg_track):
    def run():
        for _ in range(50):
            s = vibrissa.solve_point(small_whisker, [0.02, 0.004, 0.0])
            s.to_dict()
            s.shape_W, s.whisker_frame.force
            vibrissa.solve_point_batch(small_whisker, peg_track).to_dict()

    run()
    gc.collect()
    n0 = len(gc.get_objects())
    run()
    gc.collect()
    assert len(gc.get_objects()) - n0 < 50
