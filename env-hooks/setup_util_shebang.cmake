# Run by `make install` (CMakeLists.txt: install(SCRIPT ...)), after catkin installed the
# workspace's _setup_util.py: its first line names the Python that configured the build (often
# a venv's); it needs only the standard library, so the install space runs it with the python3
# on PATH and keeps working when that venv is moved or deleted.
set(_setup_util "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}/_setup_util.py")
if(EXISTS "${_setup_util}")
  file(READ "${_setup_util}" _text)
  string(REGEX REPLACE "^#![^\n]*" "#!/usr/bin/env python3" _text "${_text}")
  file(WRITE "${_setup_util}" "${_text}")
endif()
