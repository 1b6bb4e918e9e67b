"""Shared fixtures. The package under test is the one on PYTHONPATH (ctest sets <build>/python)."""

import os
import pathlib

import numpy as np
import pytest

import vibrissa


def find_cli():
    """The `vibrissa` executable of the same build: $VIBRISSA_CLI, else <build>/bin/vibrissa next to the
    extension module (<build>/python/vibrissa/_vibrissa*.so)."""
    env = os.environ.get("VIBRISSA_CLI")
    if env and os.path.isfile(env):
        return env
    build = pathlib.Path(vibrissa._vibrissa.__file__).resolve().parents[2]
    candidate = build / "bin" / "vibrissa"
    if candidate.is_file():
        return str(candidate)
    return None


@pytest.fixture(scope="session")
def cli():
    path = find_cli()
    if path is None:
        pytest.skip("the vibrissa CLI of this build was not found (set VIBRISSA_CLI)")
    return path


@pytest.fixture(scope="session")
def whisker():
    """A C2-like whisker (spec §2.1 defaults): 30 mm, y = 20 x^2, at the origin along +x."""
    return vibrissa.Whisker.from_parabola(0.03, 20.0)


@pytest.fixture(scope="session")
def small_whisker():
    """A coarser whisker for batch tests (fast)."""
    return vibrissa.Whisker.from_parabola(0.03, 20.0, properties=vibrissa.WhiskerProperties(links=40))


@pytest.fixture
def peg_track():
    """A peg passing the whisker: 12 frames of contact points [m] moving toward +y."""
    f = np.linspace(0.0, 1.0, 12)
    return np.column_stack([0.02 - 0.002 * f, 0.004 + 0.002 * f, 0.001 * f])
