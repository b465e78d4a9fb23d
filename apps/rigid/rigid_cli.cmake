# The rigid command line as a library, rigid_cli: every source of apps/rigid but program.cpp
# (main()). The `rigid` executable links it, and so do the fuzz replay and the cli_args fuzz
# target (fuzz/CMakeLists.txt includes this file when RIGID_BUILD_APPS is off, as in the asan
# and fuzz presets). CLI11 is header-only and slow to compile: only main.cpp includes it, so
# each executable holds one CLI11 translation unit. Each subcommand's options live in
# cli_<verb>.hpp (included by main.cpp alone) and its work in cmd_<verb>.cpp, which sees plain
# option structs. Source properties are per directory: this file is included in the directory
# that builds the library.
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
set(_rigid_cli_dir ${PROJECT_SOURCE_DIR}/apps/rigid)
add_library(rigid_cli STATIC
  ${_rigid_cli_dir}/main.cpp
  ${_rigid_cli_dir}/cmd_demo.cpp
  ${_rigid_cli_dir}/cmd_emit.cpp
  ${_rigid_cli_dir}/cmd_inertia.cpp
  ${_rigid_cli_dir}/cmd_inertia_fix.cpp
  ${_rigid_cli_dir}/cmd_mesh.cpp
  ${_rigid_cli_dir}/cmd_modes.cpp
  ${_rigid_cli_dir}/cmd_plot.cpp
  ${_rigid_cli_dir}/cmd_regressor.cpp
  ${_rigid_cli_dir}/cmd_rotation.cpp
  ${_rigid_cli_dir}/cmd_run.cpp
  ${_rigid_cli_dir}/cmd_sweep.cpp
  ${_rigid_cli_dir}/scene_output.cpp
)
target_include_directories(rigid_cli PUBLIC ${_rigid_cli_dir})
target_link_libraries(rigid_cli PUBLIC rigid::common rigid::io rigid::mass rigid::mesh rigid::lie
  rigid::body rigid::scene rigid::report rigid::robot
  PRIVATE CLI11::CLI11 nlohmann_json::nlohmann_json)
rigid_set_warnings(rigid_cli)
# MPI (Debian libopenmpi-dev) for `rigid sweep` under mpirun; only cmd_sweep.cpp calls it, and
# only when launched by mpirun. Without it, a sweep runs on the threads of one process.
# The C API (MPI_Init, MPI_Gatherv) through FindMPI's CXX component, which needs no C language
# in the project; the deprecated C++ bindings are left out.
set(MPI_CXX_SKIP_MPICXX ON)
find_package(MPI COMPONENTS CXX)
if(MPI_CXX_FOUND)
  target_link_libraries(rigid_cli PUBLIC MPI::MPI_CXX)
  set_source_files_properties(${_rigid_cli_dir}/cmd_sweep.cpp PROPERTIES COMPILE_DEFINITIONS RIGID_HAVE_MPI)
endif()
# `rigid demo` finds the example scenes from the executable: <prefix>/share/rigid/examples when
# installed (<prefix>/bin/rigid), the source tree's from the rigid of a build directory.
include(GNUInstallDirs)
set(RIGID_INSTALL_EXAMPLESDIR ${CMAKE_INSTALL_DATADIR}/rigid/examples)
# the path from the installed executable's directory to the examples (both under the prefix
# unless given absolute, so the same whatever --prefix `cmake --install` gets)
file(RELATIVE_PATH _rigid_examples_from_bin ${CMAKE_INSTALL_FULL_BINDIR}
     ${CMAKE_INSTALL_PREFIX}/${RIGID_INSTALL_EXAMPLESDIR})
if(IS_ABSOLUTE ${CMAKE_INSTALL_DATADIR})
  set(_rigid_examples_from_bin ${RIGID_INSTALL_EXAMPLESDIR})
endif()
# the build's rigid (none without RIGID_BUILD_APPS: the fuzz builds run no demo)
if(RIGID_BUILD_APPS)
  set(_rigid_build_bin "$<TARGET_FILE_DIR:rigid>")
else()
  set(_rigid_build_bin "${CMAKE_RUNTIME_OUTPUT_DIRECTORY}")
endif()
set_property(SOURCE ${_rigid_cli_dir}/cmd_demo.cpp APPEND PROPERTY COMPILE_DEFINITIONS
  "RIGID_EXAMPLES_FROM_BIN=\"${_rigid_examples_from_bin}\""
  "RIGID_SOURCE_EXAMPLES=\"${PROJECT_SOURCE_DIR}/examples\""
  "RIGID_BUILD_BIN_DIR=\"${_rigid_build_bin}\"")
