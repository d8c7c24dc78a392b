# The public headers: strahl/strahl.h and every strahl header it includes, directly or not
# (followed through the #include "strahl/..." lines of the sources, at install time, so the list
# cannot go stale). Everything else under src/strahl is internal and is not installed.
#   strahl_public_headers(<source dir of the headers> <output variable>)
cmake_policy(PUSH)
cmake_policy(VERSION 3.25)  # also when included by an install script, which starts with old policies

function(strahl_public_headers src_dir out)
  set(todo strahl/strahl.h)
  set(done "")
  while(todo)
    list(POP_FRONT todo header)
    if(header IN_LIST done OR header STREQUAL "strahl/version.h")  # version.h is generated
      continue()
    endif()
    list(APPEND done ${header})
    file(STRINGS "${src_dir}/${header}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"strahl/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^[^\"]*\"(strahl/[^\"]+)\".*$" "\\1" included "${line}")
      list(APPEND todo ${included})
    endforeach()
  endwhile()
  list(SORT done)
  set(${out} ${done} PARENT_SCOPE)
endfunction()

# At install time (install(CODE) in cmake/Install.cmake sets the two variables): copy them,
# keeping their folders.
if(DEFINED STRAHL_INSTALL_HEADERS_FROM)
  strahl_public_headers("${STRAHL_INSTALL_HEADERS_FROM}" headers)
  foreach(header IN LISTS headers)
    get_filename_component(dir "${header}" DIRECTORY)
    file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/${STRAHL_INSTALL_HEADERS_TO}/${dir}" TYPE FILE
         FILES "${STRAHL_INSTALL_HEADERS_FROM}/${header}")
  endforeach()
endif()

cmake_policy(POP)
