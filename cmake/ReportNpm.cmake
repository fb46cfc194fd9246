# Installs the report's pinned JavaScript libraries (report/package.json and
# package-lock.json) with `npm ci --ignore-scripts` into DST, then copies the
# files the report embeds, and their licences, into DST/assets. Run by the
# build (core/CMakeLists.txt) as: cmake -DNPM=... -DSRC=... -DDST=... -P this.
# Offline: node_modules left by an earlier install are kept when npm fails;
# with none, the build stops with a message saying what to do.
set(wanted
  three/build/three.min.js
  three/examples/js/controls/OrbitControls.js
  three/LICENSE
  uplot/dist/uPlot.iife.min.js
  uplot/dist/uPlot.min.css
  uplot/LICENSE)
file(MAKE_DIRECTORY ${DST})
configure_file(${SRC}/package.json ${DST}/package.json COPYONLY)
configure_file(${SRC}/package-lock.json ${DST}/package-lock.json COPYONLY)
set(result 1)
if(NPM)
  execute_process(COMMAND ${NPM} ci --ignore-scripts --no-audit --no-fund --prefer-offline
                  WORKING_DIRECTORY ${DST} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
endif()
set(have TRUE)
foreach(f ${wanted})
  if(NOT EXISTS ${DST}/node_modules/${f})
    set(have FALSE)
  endif()
endforeach()
if(NOT result EQUAL 0)
  if(NOT have)
    message(FATAL_ERROR "touchcloud report: `npm ci --ignore-scripts` in ${DST} failed and no earlier "
      "node_modules holds the report's JavaScript libraries (three, uplot; pinned in report/package-lock.json). "
      "Install Debian's npm (scripts/install-deps.sh) and build once with access to the npm registry "
      "(or a filled npm cache). npm said:\n${out}")
  endif()
  message(WARNING "touchcloud report: npm ci failed; using the libraries an earlier install left in ${DST}/node_modules")
endif()
file(MAKE_DIRECTORY ${DST}/assets)
foreach(f ${wanted})
  string(REPLACE "/" "_" flat ${f})
  file(COPY_FILE ${DST}/node_modules/${f} ${DST}/assets/${flat})
endforeach()
file(TOUCH ${DST}/assets/stamp)
