# The sanitizer build's default options (cmake/asan_default_options.cc) in every executable of
# this project: ASan reads __asan_default_options from the program itself (a shared library's
# definition would lose to the runtime's own), so the test binaries, the relief binary run by
# a test script or a Slurm job, and the benchmarks all get them without an environment.
function(relief_add_sanitizer_defaults directory)
  get_property(targets DIRECTORY "${directory}" PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      target_sources(${target} PRIVATE ${PROJECT_SOURCE_DIR}/cmake/asan_default_options.cc)
    endif()
  endforeach()
  get_property(subdirectories DIRECTORY "${directory}" PROPERTY SUBDIRECTORIES)
  foreach(subdirectory IN LISTS subdirectories)
    relief_add_sanitizer_defaults("${subdirectory}")
  endforeach()
endfunction()
