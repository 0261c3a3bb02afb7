# grains_module(NAME DIRS dir... [LIBS lib...])
# A static library from every .cpp in the given folders (relative to the
# current source dir); an INTERFACE library when the folders hold headers only.
# Include root is the project root, so headers are included as "sim/state/particle_store.hpp".
function(grains_module name)
  cmake_parse_arguments(M "" "" "DIRS;LIBS" ${ARGN})
  set(srcs)
  foreach(d ${M_DIRS})
    file(GLOB s CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${d}/*.cpp)
    list(APPEND srcs ${s})
  endforeach()
  if(srcs)
    add_library(${name} STATIC ${srcs})
    target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/generated)
    target_link_libraries(${name} PUBLIC ${M_LIBS})
  else()
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/generated)
    target_link_libraries(${name} INTERFACE ${M_LIBS})
  endif()
endfunction()

# grains_test(NAME SOURCES src... [LIBS lib...] [LABELS l...] [TIMEOUT s] [OFFSCREEN_RENDER])
# One GoogleTest executable; its tests are registered with CTest individually.
# OFFSCREEN_RENDER: the tests render with VTK and Mesa; in a sanitized build
# they get full unwinding (the suppressions of Mesa's and VTK's own leaks name
# VTK frames above Mesa's unloaded driver) and Mesa's softpipe driver
# (llvmpipe's LLVM shader compiler makes millions of allocations, each then
# a full stack walk). docs/sanitizers.md.
function(grains_test name)
  cmake_parse_arguments(T "OFFSCREEN_RENDER" "TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE GRAINS_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  math(EXPR T_TIMEOUT "${T_TIMEOUT} * ${GRAINS_TIMEOUT_FACTOR}")
  if(NOT T_LABELS)
    set(T_LABELS unit)
  endif()
  gtest_discover_tests(${name}
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
    PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT}
    DISCOVERY_TIMEOUT 60)
  # The environment is set by a script ctest runs after the discovered list:
  # gtest_discover_tests' PROPERTIES cannot carry a list value (it split
  # ENVIRONMENT "A;B" into a value and a stray property name).
  set(env "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")
  set(env_mod "")
  if(T_OFFSCREEN_RENDER AND GRAINS_MPI_SANITIZER_ENV)
    set(env_mod " ENVIRONMENT_MODIFICATION \"${GRAINS_MPI_SANITIZER_ENV};GALLIUM_DRIVER=set:softpipe\"")
  endif()
  set(env_file ${CMAKE_CURRENT_BINARY_DIR}/${name}_environment.cmake)
  file(WRITE ${env_file} "if(${name}_TESTS)\n  set_tests_properties(\${${name}_TESTS} PROPERTIES ENVIRONMENT \"${env}\"${env_mod})\nendif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${env_file})
endfunction()

# Add every immediate sub-folder that has its own CMakeLists.txt, so that a new
# module or test folder needs no edit of its parent.
function(grains_add_subdirs)
  file(GLOB children RELATIVE ${CMAKE_CURRENT_SOURCE_DIR} CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*/CMakeLists.txt)
  list(SORT children)
  foreach(c ${children})
    get_filename_component(d ${c} DIRECTORY)
    add_subdirectory(${d})
  endforeach()
endfunction()

# grains_mpi_test_env(test...): tests that start processes under mpirun get
# full stack unwinding for LeakSanitizer in a sanitized build (no-op otherwise).
function(grains_mpi_test_env)
  if(GRAINS_MPI_SANITIZER_ENV)
    set_tests_properties(${ARGN} PROPERTIES ENVIRONMENT_MODIFICATION "${GRAINS_MPI_SANITIZER_ENV}")
  endif()
endfunction()
