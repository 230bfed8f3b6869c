# relief_embed_files: compiles files into a C++ source, as raw string literals or byte arrays,
# through a template; the one loop that does it for every directory.
#
#   relief_embed_files(<output>
#     TEMPLATE <template>
#     FILES <path>...
#     [NAMES <name>...]
#     [NAME_WE]
#     [BYTES]
#     [DELIMITER <delimiter>]
#     FORMAT <variable> <pattern> [<variable> <pattern>]...)
#
# For every file, in order, each FORMAT <pattern> is appended as a line to the variable
# <variable>, with these placeholders replaced:
#   <NAME>  the file's name: its entry of NAMES (one per file), or else its file name (without
#           the extension with NAME_WE),
#   <ID>    <NAME> made a C identifier ("basis/alpine" -> basis_alpine),
#   <DATA>  the file's contents as a C++ expression: R"<delimiter>(...)<delimiter>", the
#           delimiter relief_embed unless DELIMITER names another; with BYTES, a braced list
#           of its bytes {0x89,0x50,...,} for an unsigned char array.
# <output> (relative: to the current binary directory) is then <template> (relative: to the
# current source directory) configured with @ONLY, each @<variable>@ replaced by its lines.
# Relative FILES are read from the current source directory.
#
# The files are read at build time, not at configure time, by this file run as a script
# (cmake -P), so a file that another custom command generates can be embedded, and an edited
# file rebuilds only <output>. Add <output> to the sources of a target of the same directory.
#
# Example (gpu/CMakeLists.txt):
#   relief_embed_files(gl_shader_sources.cc TEMPLATE gl_shader_sources.cc.in
#                      FILES shaders/fbm.comp ... DELIMITER relief_glsl
#                      FORMAT RELIEF_SHADER_ENTRIES "    {\"<NAME>\", <DATA>},")
# makes the lines {"fbm.comp", R"relief_glsl(...)relief_glsl"}, of @RELIEF_SHADER_ENTRIES@.

# Writes a CMake string as a bracket argument, which needs no escapes.
function(_relief_embed_quote out value)
  if(value MATCHES "]==]")
    message(FATAL_ERROR "relief_embed_files: ${value} contains ]==]")
  endif()
  set(${out} "[==[${value}]==]" PARENT_SCOPE)
endfunction()

function(relief_embed_files output)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "BYTES;NAME_WE" "TEMPLATE;DELIMITER" "FILES;NAMES;FORMAT")
  if(ARG_UNPARSED_ARGUMENTS OR NOT ARG_TEMPLATE OR NOT ARG_FILES OR NOT ARG_FORMAT)
    message(FATAL_ERROR "relief_embed_files(${output}): needs TEMPLATE, FILES and FORMAT "
                        "(unexpected: ${ARG_UNPARSED_ARGUMENTS})")
  endif()
  cmake_path(ABSOLUTE_PATH output BASE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  cmake_path(ABSOLUTE_PATH ARG_TEMPLATE BASE_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
  set(files "")
  foreach(file IN LISTS ARG_FILES)
    cmake_path(ABSOLUTE_PATH file BASE_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
    list(APPEND files ${file})
  endforeach()
  set(names ${ARG_NAMES})
  if(NOT ARG_NAMES)
    foreach(file IN LISTS files)
      if(ARG_NAME_WE)
        get_filename_component(name ${file} NAME_WE)
      else()
        get_filename_component(name ${file} NAME)
      endif()
      list(APPEND names ${name})
    endforeach()
  endif()
  list(LENGTH files file_count)
  list(LENGTH names name_count)
  list(LENGTH ARG_FORMAT format_length)
  math(EXPR format_odd "${format_length} % 2")
  if(NOT file_count EQUAL name_count OR format_odd)
    message(FATAL_ERROR "relief_embed_files(${output}): one NAMES entry per file, and FORMAT "
                        "in pairs of a variable and a pattern")
  endif()
  if(NOT ARG_DELIMITER)
    set(ARG_DELIMITER relief_embed)
  endif()

  # The job, read by the script at build time; rewritten only when it changes.
  set(job "")
  foreach(variable output files names ARG_TEMPLATE ARG_BYTES ARG_DELIMITER)
    _relief_embed_quote(value "${${variable}}")
    string(APPEND job "set(RELIEF_EMBED_${variable} ${value})\n")
  endforeach()
  set(index 0)
  foreach(item IN LISTS ARG_FORMAT)  # variable, pattern, variable, pattern, ...
    _relief_embed_quote(value "${item}")
    string(APPEND job "set(RELIEF_EMBED_FORMAT_${index} ${value})\n")
    math(EXPR index "${index} + 1")
  endforeach()
  string(APPEND job "set(RELIEF_EMBED_FORMAT_LENGTH ${index})\n")
  get_filename_component(output_name ${output} NAME)
  string(MAKE_C_IDENTIFIER "${output}" job_name)  # one job per output, wherever it lies
  set(job_file ${CMAKE_CURRENT_BINARY_DIR}/CMakeFiles/relief_embed/${job_name}.cmake)
  file(WRITE ${job_file}.new "${job}")
  configure_file(${job_file}.new ${job_file} COPYONLY)

  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DRELIEF_EMBED_JOB=${job_file} -P ${CMAKE_CURRENT_FUNCTION_LIST_FILE}
    DEPENDS ${files} ${ARG_TEMPLATE} ${job_file} ${CMAKE_CURRENT_FUNCTION_LIST_FILE}
    COMMENT "Embedding ${file_count} files in ${output_name}"
    VERBATIM)
endfunction()

# Script mode: the build step of one relief_embed_files call.
if(CMAKE_SCRIPT_MODE_FILE AND DEFINED RELIEF_EMBED_JOB)
  include(${RELIEF_EMBED_JOB})
  math(EXPR last "${RELIEF_EMBED_FORMAT_LENGTH} - 1")
  foreach(index RANGE 0 ${last} 2)
    set(lines_${index} "")
  endforeach()
  set(delimiter ${RELIEF_EMBED_ARG_DELIMITER})
  foreach(file name IN ZIP_LISTS RELIEF_EMBED_files RELIEF_EMBED_names)
    if(RELIEF_EMBED_ARG_BYTES)
      file(READ ${file} hex HEX)
      string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
      set(data "{${bytes}}")
    else()
      file(READ ${file} text)
      string(FIND "${text}" ")${delimiter}\"" clash)
      if(NOT clash EQUAL -1)
        message(FATAL_ERROR "${file} contains )${delimiter}\", which would end its raw string")
      endif()
      set(data "R\"${delimiter}(${text})${delimiter}\"")
    endif()
    string(MAKE_C_IDENTIFIER "${name}" id)
    foreach(index RANGE 0 ${last} 2)
      math(EXPR pattern_index "${index} + 1")
      set(line "${RELIEF_EMBED_FORMAT_${pattern_index}}")
      # <DATA> last, so that a file's text is never searched for placeholders.
      string(REPLACE "<NAME>" "${name}" line "${line}")
      string(REPLACE "<ID>" "${id}" line "${line}")
      string(REPLACE "<DATA>" "${data}" line "${line}")
      string(APPEND lines_${index} "${line}\n")
    endforeach()
  endforeach()
  foreach(index RANGE 0 ${last} 2)
    set(${RELIEF_EMBED_FORMAT_${index}} "${lines_${index}}")
  endforeach()
  file(READ ${RELIEF_EMBED_ARG_TEMPLATE} template)
  string(CONFIGURE "${template}" configured @ONLY)
  file(WRITE ${RELIEF_EMBED_output} "${configured}")
endif()
