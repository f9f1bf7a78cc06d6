# Writes OUTPUT, a header with what the engine ENGINE prints for --help,
# --version and --list-scenes (run at build time; none of them starts MPI),
# for the launcher (source/launcher.cc).
foreach(request help version list-scenes)
  execute_process(COMMAND ${ENGINE} --${request} OUTPUT_VARIABLE text${request}
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${ENGINE} --${request} failed (${result})")
  endif()
endforeach()
file(WRITE ${OUTPUT}.new "#pragma once
// Generated from the engine's own answers (cmake/engine_information.cmake).
namespace granular_dg::engine_information
{
  inline constexpr const char *help = R\"granular_dg(${texthelp})granular_dg\";
  inline constexpr const char *version = R\"granular_dg(${textversion})granular_dg\";
  inline constexpr const char *scenes = R\"granular_dg(${textlist-scenes})granular_dg\";
}
")
file(COPY_FILE ${OUTPUT}.new ${OUTPUT} ONLY_IF_DIFFERENT)
