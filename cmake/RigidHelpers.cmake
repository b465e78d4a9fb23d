# Shared CMake helpers: one function builds a module, one builds a module's test executable.

# Warnings are PRIVATE to each of our targets so that they never leak into a consumer.
function(rigid_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
    -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough)
  if(RIGID_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# Records a line for rigidConfig.cmake, e.g. rigid_config_dependency("find_dependency(Boost 1.74)").
function(rigid_config_dependency line)
  set_property(GLOBAL APPEND PROPERTY RIGID_CONFIG_DEPENDENCIES "${line}")
endfunction()

# rigid_add_module(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Makes the static library rigid_<name>, its alias rigid::<name>, and exports it.
function(rigid_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(rigid_${name} ${ARG_SOURCES})
  add_library(rigid::${name} ALIAS rigid_${name})
  set_target_properties(rigid_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(rigid_${name}
    PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
           $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_compile_features(rigid_${name} PUBLIC cxx_std_20)
  target_link_libraries(rigid_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  rigid_set_warnings(rigid_${name})
  set_property(GLOBAL APPEND PROPERTY RIGID_MODULES rigid_${name})
  install(TARGETS rigid_${name} EXPORT rigidTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
endfunction()
