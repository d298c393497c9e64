# Install-time script (apps/CMakeLists.txt): writes one man page per srp command and subcommand with
# help2man from the command's own --help, and installs them to <prefix>/share/man/man1.
# Inputs: SRP_EXE (the built srp), SRP_HELP2MAN, SRP_MAN_DIR (a scratch folder), SRP_VERSION.
# The machine's "Data folder: ..." line of srp --help is left out of the pages.
file(REMOVE_RECURSE "${SRP_MAN_DIR}")
file(MAKE_DIRECTORY "${SRP_MAN_DIR}/bin")
file(WRITE "${SRP_MAN_DIR}/bin/srp" "#!/bin/sh\n\"${SRP_EXE}\" \"$@\" | grep -v '^Data folder:'\n")
file(CHMOD "${SRP_MAN_DIR}/bin/srp" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
     WORLD_READ WORLD_EXECUTE)

# The subcommands of `srp <path> --help` as a list of "name|description".
function(srp_subcommands path out)
  execute_process(COMMAND "${SRP_EXE}" ${path} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "srp ${path} --help failed (${rc})")
  endif()
  string(REPLACE ";" "," help "${help}")
  string(REPLACE "\n" ";" lines "${help}")
  set(in_subcommands FALSE)
  set(result)
  foreach(line IN LISTS lines)
    if(line MATCHES "^Subcommands:")
      set(in_subcommands TRUE)
    elseif(in_subcommands AND line MATCHES "^  ([a-z][a-z0-9-]*) +(.*)$")
      list(APPEND result "${CMAKE_MATCH_1}|${CMAKE_MATCH_2}")
    elseif(NOT line MATCHES "^ ")
      set(in_subcommands FALSE)
    endif()
  endforeach()
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

function(srp_man_page path description)
  if(path STREQUAL "")
    set(page srp)
  else()
    string(REPLACE ";" "-" page "srp;${path}")
  endif()
  string(REPLACE ";" " " words "${path}")
  execute_process(
    COMMAND "${SRP_HELP2MAN}" --no-info --no-discard-stderr "--version-string=${page} ${SRP_VERSION}"
            "--name=${description}" --section=1 --output=${SRP_MAN_DIR}/${page}.1
            "${SRP_MAN_DIR}/bin/srp ${words}"
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "help2man failed on 'srp ${words}' (${rc})")
  endif()
endfunction()

srp_man_page("" "semantic robot programming: one instruction and one RGB-D demonstration to a UR5 program")
srp_subcommands("" commands)
foreach(entry IN LISTS commands)
  string(REPLACE "|" ";" parts "${entry}")
  list(GET parts 0 name)
  list(GET parts 1 description)
  srp_man_page("${name}" "${description}")
  srp_subcommands("${name}" subs)
  foreach(sub IN LISTS subs)
    string(REPLACE "|" ";" sparts "${sub}")
    list(GET sparts 0 sname)
    list(GET sparts 1 sdescription)
    srp_man_page("${name};${sname}" "${sdescription}")
  endforeach()
endforeach()
file(GLOB pages "${SRP_MAN_DIR}/*.1")
file(INSTALL ${pages} DESTINATION "${CMAKE_INSTALL_PREFIX}/share/man/man1")
