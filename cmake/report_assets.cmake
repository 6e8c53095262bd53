# The HTML report's page (docs/report-data.md): web/ is an npm project (three.js, uPlot, esbuild) whose bundle
# is compiled into pkm. Node.js and npm come from scripts/install-deps.sh; the packages are installed here,
# at configure time, from web/package-lock.json (never vendored).
#
# Without Node.js (or with -DPKM_REPORT_PAGE=OFF) everything else builds: the page is left out, one line says
# so, and a report asked for fails with a message saying why (report_page_built() is false).
option(PKM_REPORT_PAGE "Build the HTML report page (needs Node.js and npm)" ON)
set(pkm_no_page_reason "PKM_REPORT_PAGE is OFF")
if(PKM_REPORT_PAGE)
  find_program(PKM_NODE node)
  find_program(PKM_NPM npm)
  # A cached path that no longer exists (Node.js removed since, or -DPKM_NODE=/none to build as without it)
  # counts as not found.
  if(NOT PKM_NODE OR NOT PKM_NPM OR NOT EXISTS "${PKM_NODE}" OR NOT EXISTS "${PKM_NPM}")
    set(pkm_no_page_reason "Node.js or npm not found (scripts/install-deps.sh installs them: nodejs, npm)")
    set(PKM_REPORT_PAGE OFF)
  endif()
endif()
if(NOT PKM_REPORT_PAGE)
  message(STATUS "pkm: building without the HTML report page: ${pkm_no_page_reason}; a report asked for fails "
                 "saying so")
  add_library(pkm_report_assets STATIC ${PROJECT_SOURCE_DIR}/cmake/report_page_missing.cpp)
  target_include_directories(pkm_report_assets PRIVATE ${PROJECT_SOURCE_DIR}/src)
  return()
endif()
set(PKM_WEB_DIR ${PROJECT_SOURCE_DIR}/web)
# Installed again when the lock file is newer than the installed tree (npm writes node_modules/.package-lock.json).
if(NOT EXISTS ${PKM_WEB_DIR}/node_modules/.package-lock.json
   OR ${PKM_WEB_DIR}/package-lock.json IS_NEWER_THAN ${PKM_WEB_DIR}/node_modules/.package-lock.json)
  message(STATUS "pkm: installing the report page's npm packages (web/package-lock.json)")
  execute_process(COMMAND ${PKM_NPM} ci --no-audit --no-fund --loglevel=error
                  WORKING_DIRECTORY ${PKM_WEB_DIR} RESULT_VARIABLE pkm_npm_result)
  if(NOT pkm_npm_result EQUAL 0)
    message(FATAL_ERROR "npm ci in ${PKM_WEB_DIR} failed (${pkm_npm_result}): the report page cannot be built")
  endif()
endif()
file(GLOB PKM_WEB_SOURCES CONFIGURE_DEPENDS ${PKM_WEB_DIR}/src/*)
set(PKM_WEB_OUT ${PROJECT_BINARY_DIR}/web)
add_custom_command(
  OUTPUT ${PKM_WEB_OUT}/report.bundle.js ${PKM_WEB_OUT}/report.css
  COMMAND ${PKM_NODE} ${PKM_WEB_DIR}/build.mjs --out ${PKM_WEB_OUT}
  DEPENDS ${PKM_WEB_SOURCES} ${PKM_WEB_DIR}/build.mjs ${PKM_WEB_DIR}/package-lock.json
  COMMENT "Bundling the report page (web/)"
  VERBATIM)
add_custom_command(
  OUTPUT ${PROJECT_BINARY_DIR}/generated/report_assets.cpp
  COMMAND ${CMAKE_COMMAND} -DSCRIPT=${PKM_WEB_OUT}/report.bundle.js -DSTYLE=${PKM_WEB_OUT}/report.css
          -DOUT=${PROJECT_BINARY_DIR}/generated/report_assets.cpp -P ${PROJECT_SOURCE_DIR}/cmake/embed_report_assets.cmake
  DEPENDS ${PKM_WEB_OUT}/report.bundle.js ${PKM_WEB_OUT}/report.css
          ${PROJECT_SOURCE_DIR}/cmake/embed_report_assets.cmake
  VERBATIM)
add_library(pkm_report_assets STATIC ${PROJECT_BINARY_DIR}/generated/report_assets.cpp)
target_include_directories(pkm_report_assets PRIVATE ${PROJECT_SOURCE_DIR}/src)
