# The libraries for the Windows cross build (cmake/mingw-w64.cmake): Boost,
# spdlog and fmt as every cross build takes them, then the manifest.
include(${CMAKE_CURRENT_LIST_DIR}/cross-deps.cmake)

# Both programs carry cmake/windows.manifest: UTF-8 as their code page.
enable_language(RC)
set(SCAFFOLD_WINDOWS_RESOURCES "${CMAKE_CURRENT_LIST_DIR}/windows-manifest.rc")
