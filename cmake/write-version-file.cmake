# Writes mtcutConfigVersion.cmake with CMake's own helper (SameMajorVersion: a request for
# X.Y is satisfied by this package when the majors match and this version is not older).
# Run by scripts/install.sh:
#   cmake -DOUT=FILE -DVERSION=X.Y.Z -DSIZEOF_VOID_P=8 -P cmake/write-version-file.cmake
include(CMakePackageConfigHelpers)
# The helper also refuses a consumer of another pointer size (32- vs 64-bit): it takes the
# size from this variable, which script mode does not set.
set(CMAKE_SIZEOF_VOID_P "${SIZEOF_VOID_P}")
write_basic_package_version_file("${OUT}" VERSION "${VERSION}" COMPATIBILITY SameMajorVersion)
