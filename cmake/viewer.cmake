# The report viewer (viewer/: TypeScript, three.js, uPlot, bundled by Vite into ONE HTML file), built
# with the machine's node and npm and embedded into tumble_io as report_template() (io/report.hpp).
# Without node and npm the library still builds: `tumble run --report` then says how to get it.
option(TUMBLE_BUILD_VIEWER "Build the report viewer (needs node and npm)" ON)
find_program(TUMBLE_NPM npm)
find_program(TUMBLE_NODE node)
set(TUMBLE_REPORT_TEMPLATE_CPP ${PROJECT_BINARY_DIR}/generated/report_template.cpp)
if(TUMBLE_BUILD_VIEWER AND TUMBLE_NPM AND TUMBLE_NODE)
  set(viewer ${PROJECT_SOURCE_DIR}/viewer)
  set(TUMBLE_REPORT_BUNDLE ${viewer}/dist/report.html)
  set(TUMBLE_VIEWER_FOUND ON CACHE INTERNAL "the report viewer is built (tests/ runs its tests)")
  # npm ci when the lockfile changes (a stamp in node_modules), the bundle when a source changes.
  add_custom_command(OUTPUT ${viewer}/node_modules/.tumble-installed
                     COMMAND ${TUMBLE_NPM} ci --no-audit --no-fund --loglevel=error
                     COMMAND ${CMAKE_COMMAND} -E touch ${viewer}/node_modules/.tumble-installed
                     DEPENDS ${viewer}/package-lock.json ${viewer}/package.json
                     WORKING_DIRECTORY ${viewer} COMMENT "viewer: npm ci" VERBATIM)
  file(GLOB_RECURSE viewer_sources CONFIGURE_DEPENDS ${viewer}/src/*)
  file(GLOB viewer_files CONFIGURE_DEPENDS ${viewer}/*.html ${viewer}/*.config.ts ${viewer}/tsconfig.json)
  list(APPEND viewer_sources ${viewer_files})
  add_custom_command(OUTPUT ${TUMBLE_REPORT_BUNDLE}
                     COMMAND ${TUMBLE_NPM} run build --silent
                     DEPENDS ${viewer}/node_modules/.tumble-installed ${viewer_sources}
                     WORKING_DIRECTORY ${viewer} COMMENT "viewer: npm run build" VERBATIM)
  add_custom_command(OUTPUT ${TUMBLE_REPORT_TEMPLATE_CPP}
                     COMMAND ${CMAKE_COMMAND} -DINPUT=${TUMBLE_REPORT_BUNDLE} -DOUTPUT=${TUMBLE_REPORT_TEMPLATE_CPP}
                             -DSYMBOL=report_template -P ${PROJECT_SOURCE_DIR}/cmake/embed_file.cmake
                     DEPENDS ${TUMBLE_REPORT_BUNDLE} ${PROJECT_SOURCE_DIR}/cmake/embed_file.cmake
                     COMMENT "viewer: embedding report.html" VERBATIM)
  message(STATUS "tumble: report viewer built with ${TUMBLE_NPM}")
else()
  set(TUMBLE_VIEWER_FOUND OFF CACHE INTERNAL "the report viewer is built (tests/ runs its tests)")
  file(WRITE ${TUMBLE_REPORT_TEMPLATE_CPP}.in
       "// No report viewer in this build (node and npm not found, or TUMBLE_BUILD_VIEWER=OFF).\n"
       "#include <string_view>\nnamespace tumble {\nstd::string_view report_template() { return {}; }\n}\n")
  configure_file(${TUMBLE_REPORT_TEMPLATE_CPP}.in ${TUMBLE_REPORT_TEMPLATE_CPP} COPYONLY)
  message(STATUS "tumble: no report viewer (node and npm not found); `tumble run --report` will say so")
endif()
