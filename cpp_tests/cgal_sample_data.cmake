# CGAL's sample meshes and point sets: libcgal-demo ships them as one tarball, so the files a
# directory needs are extracted into its build directory at configure time.
# TOPOPLEX_CGAL_DATA_DIR (configure) or $TOPOPLEX_CGAL_DATA (run time) may point at an unpacked
# CGAL data/ directory instead. Included by cpp_tests/ (whose tests skip absent files) and by
# the separate bench_data/ project (which needs them: REQUIRED makes a missing file a warning).
#
#   topoplex_cgal_sample_data(<out_var> [REQUIRED] <file>...)
# sets <out_var> to the data/ directory; files are relative to it ("meshes/elephant.off").
set(TOPOPLEX_CGAL_DATA_DIR "" CACHE PATH "CGAL sample data directory (holding meshes/ and points_3/)")
function(topoplex_cgal_sample_data out_var)
  set(files ${ARGN})
  set(mode STATUS)
  set(consequence "; tests needing it will skip")
  list(FIND files REQUIRED required)
  if(required EQUAL 0)
    list(REMOVE_AT files 0)
    set(mode WARNING)
    set(consequence "")
  endif()
  set(dir "${TOPOPLEX_CGAL_DATA_DIR}")
  if(NOT dir)
    find_file(CGAL_DEMO_DATA_TARBALL data.tar.gz
              PATHS /usr/share/doc/libcgal-demo /usr/share/doc/libcgal-dev NO_DEFAULT_PATH)
    set(dir "${CMAKE_CURRENT_BINARY_DIR}/cgal-data/data")
    set(missing "")
    foreach(f IN LISTS files)
      if(NOT EXISTS "${dir}/${f}")
        list(APPEND missing "data/${f}")
      endif()
    endforeach()
    if(missing AND CGAL_DEMO_DATA_TARBALL)
      file(ARCHIVE_EXTRACT INPUT "${CGAL_DEMO_DATA_TARBALL}"
           DESTINATION "${CMAKE_CURRENT_BINARY_DIR}/cgal-data" PATTERNS ${missing})
    elseif(missing)
      message(${mode} "${CMAKE_CURRENT_SOURCE_DIR}: CGAL sample data not found (install libcgal-demo or set TOPOPLEX_CGAL_DATA_DIR)${consequence}")
    endif()
  endif()
  set(${out_var} "${dir}" PARENT_SCOPE)
endfunction()
