# System dependencies, all from Debian 12 packages (see third_party/README.md for versions and
# licences). Nothing is downloaded at configure or build time.
find_package(embree 3 REQUIRED)          # libembree-dev 3.13.5 — target: embree
find_package(TBB REQUIRED)               # libtbb-dev 2021.8 — TBB::tbb
find_package(OpenImageIO REQUIRED)       # libopenimageio-dev 2.4 — OpenImageIO::OpenImageIO
                                         # (only in the dlopen'ed module libprism_oiio.so)
find_package(OpenEXR 3 REQUIRED CONFIG)  # libopenexr-dev 3.1 — OpenEXR::OpenEXR (EXR output)
find_package(PNG REQUIRED)               # libpng-dev 1.6 — PNG::PNG (PNG output)
find_package(fmt REQUIRED)               # libfmt-dev 9 — fmt::fmt
find_package(CLI11 REQUIRED)             # libcli11-dev 2.3 — CLI11::CLI11
find_package(tinyobjloader REQUIRED)     # libtinyobjloader-dev 2.0rc10 — tinyobjloader::tinyobjloader
find_package(TinyGLTF REQUIRED)          # libtinygltf-dev 2.7 (header-only)
find_package(Boost 1.74 REQUIRED)        # libboost-dev 1.74 (headers only: Boost.Random's
                                         # Sobol direction numbers) — Boost::headers
if(PRISM_BUILD_TESTS)
  find_package(GTest REQUIRED)           # libgtest-dev 1.12
endif()

# Debian 12's OpenImageIO config lists /usr/include/opencv4 as an include directory although
# OpenImageIO's headers never need OpenCV; drop include paths that do not exist so the build
# does not require libopencv-dev.
get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_oiio_inc)
  set(_oiio_inc_ok "")
  foreach(_d IN LISTS _oiio_inc)
    if(EXISTS "${_d}")
      list(APPEND _oiio_inc_ok "${_d}")
    endif()
  endforeach()
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_inc_ok}")
endif()
