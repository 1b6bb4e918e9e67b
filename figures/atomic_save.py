"""Atomic figure files for the scripts in figures/ (the Python side of vibrissa's io/atomic_file.hpp).

Each figure is written to a temporary beside its target (same directory, `.tmp-<pid>-<name>`, the extension
kept last so that matplotlib and ffmpeg pick the format from it), flushed to disk and renamed over the target
with os.replace(). If saving fails, or the script is interrupted or killed (SIGINT, SIGTERM, SIGHUP), the
temporary is removed and an older figure of that name is left as it was.
"""
import contextlib
import os
import signal


def _exit_on_signal(signum, _frame):
    raise SystemExit(128 + signum)  # unwinds through the `finally` below, unlike the default action


for _sig in (signal.SIGTERM, signal.SIGHUP):
    signal.signal(_sig, _exit_on_signal)


@contextlib.contextmanager
def replacing(path):
    """Yields the temporary path to write; renames it over `path` once the block completes."""
    folder, name = os.path.split(os.path.abspath(path))
    tmp = os.path.join(folder, f".tmp-{os.getpid()}-{name}")
    try:
        yield tmp
        with open(tmp, "rb") as f:
            os.fsync(f.fileno())
        os.replace(tmp, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.remove(tmp)


def save_figure(fig, path, **savefig_kwargs):
    """fig.savefig(path, ...) through a temporary."""
    with replacing(path) as tmp:
        fig.savefig(tmp, **savefig_kwargs)


def save_animation(anim, path, writer):
    """anim.save(path, writer=writer) through a temporary."""
    with replacing(path) as tmp:
        anim.save(tmp, writer=writer)
