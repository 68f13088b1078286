# SPDX-License-Identifier: MIT
# Writes a C++ source defining one string constant per text file, so the viewer's page and script
# are kept as ordinary files in the repository yet travel inside the impulse executable.
#
#   cmake -DOUTPUT=<file.cpp> -DNAMESPACE=<ns> -DFILES="<name>=<path>|..." -P embed_text.cmake
cmake_minimum_required(VERSION 3.21)
set(text "// Generated from ${FILES} by cmake/embed_text.cmake: do not edit.\nnamespace ${NAMESPACE}\n{\n")
string(REPLACE "|" ";" FILES "${FILES}")
foreach(entry IN LISTS FILES)
  string(REGEX REPLACE "=.*" "" name "${entry}")
  string(REGEX REPLACE "^[^=]*=" "" path "${entry}")
  file(READ "${path}" content)
  string(FIND "${content}" ")impulse_embedded\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${path} contains the raw-string delimiter )impulse_embedded\"")
  endif()
  string(APPEND text "extern const char* const ${name};\nconst char* const ${name} = R\"impulse_embedded(${content})impulse_embedded\";\n")
endforeach()
string(APPEND text "} // namespace ${NAMESPACE}\n")
file(WRITE "${OUTPUT}.tmp" "${text}")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
