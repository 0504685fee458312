# install_check.cmake — ctest label `install`: `cmake --install` into a fresh prefix, then the
# one-file app built against it with find_package and with pkg-config, each run: the box must
# rest on the ground (y = 0.5 m) on the GPU path. Run as
#   cmake -DBUILD_DIR=... -DWORK_DIR=... -DAPP_DIR=... -DCXX=... -P install_check.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

function(run what)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
    endif()
    set(last_output "${out}" PARENT_SCOPE)
endfunction()

function(expect_rest what)
    if(NOT last_output MATCHES "box at y = 0\\.(49[0-9]|50[0-9]), GPU path")
        message(FATAL_ERROR "${what}: expected the box at rest on the GPU path, got: ${last_output}")
    endif()
    message(STATUS "${what}: ${last_output}")
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(f include/btgpu/btGpuDynamicsWorld.h lib/cmake/btgpu lib/pkgconfig/btgpu.pc)
    if(NOT EXISTS "${prefix}/${f}")
        message(FATAL_ERROR "not installed: ${prefix}/${f}")
    endif()
endforeach()

run("configure the find_package app" ${CMAKE_COMMAND} -S "${APP_DIR}" -B "${WORK_DIR}/app-build"
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run("build the find_package app" ${CMAKE_COMMAND} --build "${WORK_DIR}/app-build")
run("run the find_package app" "${WORK_DIR}/app-build/app")
expect_rest("find_package app")

set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig")
run("pkg-config" pkg-config --cflags --libs btgpu)
string(STRIP "${last_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run("build the pkg-config app" "${CXX}" -std=c++17 -O1 "${APP_DIR}/app.cpp" ${flags} -o "${WORK_DIR}/app_pc")
run("run the pkg-config app" "${WORK_DIR}/app_pc")
expect_rest("pkg-config app")
