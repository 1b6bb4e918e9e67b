"""Renamed to carry their frame (_W): the new names equal the old ones, and the old ones still work for one
release (removed in 0.2.0) with a DeprecationWarning naming the replacement."""

import numpy as np
import pytest

import vibrissa


def test_solution_world_fields_and_their_deprecated_aliases(whisker):
    s = vibrissa.solve_point(whisker, [0.02, 0.004, 0.0])
    assert s.converged and s.shape_W.shape == (101, 3)
    for old in ("contact_point", "force", "moment", "shape"):
        with pytest.warns(DeprecationWarning, match=rf"Solution\.{old} is deprecated .* 0\.2\.0; use {old}_W"):
            value = getattr(s, old)
        np.testing.assert_array_equal(value, getattr(s, old + "_W"))
    wf = s.whisker_frame
    assert wf.Fx == wf.force[0] and wf.Mx == wf.moment[0] and wf.Fx != 0.0


def test_base_wrench_root_contact_point_alias(whisker):
    touch = vibrissa.solve_point(whisker, [0.02, 0.004, 0.0])
    found = vibrissa.solve_base_wrench(whisker, touch.force_W, touch.moment_W)
    root = found.roots[0]
    with pytest.warns(DeprecationWarning, match=r"BaseWrenchRoot\.contact_point is deprecated"):
        old = root.contact_point
    np.testing.assert_array_equal(old, root.contact_point_W)
    batch = vibrissa.solve_base_wrench_batch(whisker, touch.force_W[None, :], touch.moment_W[None, :])
    with pytest.warns(DeprecationWarning, match=r"BaseWrenchBatch\.contact_point is deprecated"):
        np.testing.assert_array_equal(batch.contact_point, batch.contact_point_W)


def test_batch_outputs_have_w_names_and_fx_mx(small_whisker, peg_track):
    batch = vibrissa.solve_point_batch(small_whisker, peg_track, shapes=True)
    for i in range(len(peg_track)):
        s = vibrissa.solve_point(small_whisker, peg_track[i], warm=None if i == 0 else prev)
        prev = s
        assert batch.whisker_frame.Fx[i] == pytest.approx(s.whisker_frame.Fx, rel=1e-12, abs=0.0)
        assert batch.whisker_frame.Mx[i] == pytest.approx(s.whisker_frame.Mx, rel=1e-12, abs=0.0)
    np.testing.assert_array_equal(batch.whisker_frame.Fx, batch.whisker_frame.force[:, 0])
    np.testing.assert_array_equal(batch.whisker_frame.Mx, batch.whisker_frame.moment[:, 0])
    assert "Fx" in batch.to_dict()["whisker_frame"] and "contact_point_W" in batch.to_dict()
    for old in ("contact_point", "force", "moment", "shape"):
        with pytest.warns(DeprecationWarning, match=rf"BatchResult\.{old} is deprecated .*; use {old}_W"):
            value = getattr(batch, old)
        np.testing.assert_array_equal(value, getattr(batch, old + "_W"))


def test_batch_old_keywords_warn_and_give_the_same_result(small_whisker, peg_track):
    direction = [0.0, 0.0, 1.0]
    new = vibrissa.solve_point_batch(small_whisker, points_W=peg_track, edge_direction_W=direction)
    with pytest.warns(DeprecationWarning, match=r"solve_point_batch\(points=\.\.\.\) is deprecated"):
        old = vibrissa.solve_point_batch(small_whisker, points=peg_track, edge_direction=direction)
    np.testing.assert_array_equal(old.force_W, new.force_W)
    np.testing.assert_array_equal(old.edge_force, new.edge_force)
    assert not np.all(np.isnan(new.edge_force))

    approach = [0.0, 1.0, 0.0]
    new = vibrissa.solve_edge_batch(small_whisker, edge_points_W=peg_track, edge_directions_W=direction,
                                    approach_W=approach)
    with pytest.warns(DeprecationWarning, match=r"solve_edge_batch\(approach=\.\.\.\) is deprecated"):
        old = vibrissa.solve_edge_batch(small_whisker, edge_points=peg_track, edge_directions=direction,
                                        approach=approach)
    np.testing.assert_array_equal(old.contact_point_W, new.contact_point_W)

    q0 = peg_track[0]
    new = vibrissa.solve_frictional_edge_batch(small_whisker, peg_track, direction, 0.3, initial_contact_W=q0)
    with pytest.warns(DeprecationWarning, match=r"initial_contact=\.\.\.\) is deprecated.*initial_contact_W="):
        old = vibrissa.solve_frictional_edge_batch(small_whisker, peg_track, direction, 0.3, initial_contact=q0)
    np.testing.assert_array_equal(old.contact_point_W, new.contact_point_W)


def test_batch_keyword_under_both_names_or_unknown_is_a_type_error(small_whisker, peg_track):
    with pytest.raises(TypeError, match=r"got 'points' and its new name 'points_W'"):
        vibrissa.solve_point_batch(small_whisker, peg_track, points=peg_track)
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'pints'"):
        vibrissa.solve_point_batch(small_whisker, peg_track, pints=peg_track)


def test_solve_json_has_w_keys_and_deprecated_copies(whisker):
    d = vibrissa.solve_point(whisker, [0.02, 0.004, 0.0]).to_dict()
    np.testing.assert_array_equal(d["contact_point_W"], d["contact_point"])
    np.testing.assert_array_equal(d["shape_W"], d["shape"])
    assert d["shape_W"].shape == (101, 3) and d["whisker_frame"]["Fx"] == d["whisker_frame"]["force"][0]
