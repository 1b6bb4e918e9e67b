# VIBRISSA_PYTHON_INSTALL_DIR: where the Python package is installed, relative to the prefix (the interpreter's
# posix_prefix layout: lib/python3.X/site-packages), so that `cmake --install build --prefix ~/.local` lands in
# the user site and `import vibrissa` needs no PYTHONPATH. For Debian's /usr/local use
# -DVIBRISSA_PYTHON_INSTALL_DIR=lib/python3/dist-packages. Used by python/ (install) and apps/ (the CLI's
# `vibrissa sweep` runs the installed package).
if(NOT DEFINED VIBRISSA_PYTHON_INSTALL_DIR)
  execute_process(COMMAND ${Python3_EXECUTABLE} -c
    "import sysconfig; print(sysconfig.get_path('platlib', 'posix_prefix', vars={'base': '', 'platbase': ''}).lstrip('/'))"
    OUTPUT_VARIABLE VIBRISSA_PYTHON_INSTALL_DIR OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(VIBRISSA_PYTHON_INSTALL_DIR "${VIBRISSA_PYTHON_INSTALL_DIR}" CACHE STRING
    "Install directory of the Python package, relative to the prefix")
endif()
