# Writes the build's version header (run at every build by the roller_version target): the git
# commit of the source tree, so `roller --version` names the code it was built from. configure_file
# rewrites the header only when its text changes, so an unchanged commit rebuilds nothing.
execute_process(COMMAND git -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE ROLLER_GIT_COMMIT OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT ROLLER_GIT_COMMIT)
  set(ROLLER_GIT_COMMIT "unknown")
endif()
configure_file("${SOURCE_DIR}/cmake/build_info.hpp.in" "${OUTPUT}" @ONLY)
