# cmake --install (and the Debian package, cmake/package.cmake): the pkm command, its man page and bash completion
# (both written from the command's own --help by scripts/gen-cli-docs.py after every build of it), and the
# licence, changelog and README as its documentation.
set(PKM_CLI_MAN ${PROJECT_BINARY_DIR}/share/pkm.1)
set(PKM_CLI_COMPLETION ${PROJECT_BINARY_DIR}/share/pkm.bash)
add_custom_command(
  OUTPUT ${PKM_CLI_MAN} ${PKM_CLI_COMPLETION}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/share
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/gen-cli-docs.py $<TARGET_FILE:pkm> --man ${PKM_CLI_MAN}
          --completion ${PKM_CLI_COMPLETION}
  DEPENDS pkm ${PROJECT_SOURCE_DIR}/scripts/gen-cli-docs.py
  COMMENT "pkm's man page and bash completion from its --help"
  VERBATIM)
add_custom_target(pkm_cli_docs ALL DEPENDS ${PKM_CLI_MAN} ${PKM_CLI_COMPLETION})

install(TARGETS pkm RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${PKM_CLI_MAN} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${PKM_CLI_COMPLETION} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions RENAME pkm)
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CHANGELOG.md ${PROJECT_SOURCE_DIR}/README.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
