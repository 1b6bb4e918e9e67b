"""The `vibrissa` command from the Python package: the console script pip installs and `python -m vibrissa`.

`vibrissa sweep ...` and `vibrissa view ...` run here (vibrissa.sweeps.main, vibrissa.viewer.main). Every other subcommand is the C++ command line, the same
executables as the CMake build's: the copy shipped in the wheel (vibrissa/bin/vibrissa, which hands the file
commands to vibrissa/libexec/vibrissa/vibrissa-full), else $VIBRISSA_CLI, else the `bin/vibrissa` of the build
tree or prefix the package lies in. The process is replaced by it (exit status and signals are the CLI's),
with this interpreter for its figure scripts ($VIBRISSA_PYTHON) and the package's copy of them
($VIBRISSA_FIGURES_DIR), unless set.
"""

import os
import pathlib
import sys

__all__ = ["cli_executable", "main"]

PACKAGE = pathlib.Path(__file__).resolve().parent


def _is_executable_program(path):
    """An ELF executable (not the console script pip writes, which would call this module again)."""
    try:
        with open(path, "rb") as f:
            return f.read(4) == b"\x7fELF" and os.access(path, os.X_OK)
    except OSError:
        return False


def cli_executable():
    """The C++ `vibrissa` executable that belongs to this package; FileNotFoundError if there is none."""
    candidates = [PACKAGE / "bin" / "vibrissa"]
    if os.environ.get("VIBRISSA_CLI"):
        candidates.append(pathlib.Path(os.environ["VIBRISSA_CLI"]))
    # <build>/python/vibrissa -> <build>/bin; <prefix>/lib/python3.X/site-packages/vibrissa -> <prefix>/bin.
    candidates += [ancestor / "bin" / "vibrissa" for ancestor in list(PACKAGE.parents)[:4]]
    for candidate in candidates:
        if _is_executable_program(candidate):
            return candidate
    raise FileNotFoundError("the vibrissa command-line executable was not found (looked for "
                            + ", ".join(map(str, candidates)) + "); set VIBRISSA_CLI to its path")


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv and argv[0] == "sweep":
        from .sweeps import main as sweep_main
        return sweep_main(argv[1:])
    if argv and argv[0] == "view":
        from .viewer import main as view_main
        return view_main(argv[1:])
    try:
        executable = cli_executable()
    except FileNotFoundError as error:
        print(f"vibrissa: error: {error}", file=sys.stderr)
        return 1
    env = dict(os.environ)
    env.setdefault("VIBRISSA_PYTHON", sys.executable)
    if (PACKAGE / "figures" / "trial_figures.py").is_file():
        env.setdefault("VIBRISSA_FIGURES_DIR", str(PACKAGE / "figures"))
    sys.stdout.flush()
    os.execve(executable, [str(executable), *argv], env)
