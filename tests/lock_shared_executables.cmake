# A test that runs both serially and with mpirun=N builds one executable for
# both variants. deal.II's macro orders the variants only when every one of
# them has an mpirun count, so under ctest -j the serial variant could start
# running the executable while the other variant relinks it ("Text file
# busy"). Give each such pair one resource lock so that they never overlap.
# Include after deal_ii_pickup_tests() in a category's CMakeLists.txt.
get_filename_component(_category ${CMAKE_CURRENT_SOURCE_DIR} NAME)
file(GLOB _mpi_outputs RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}
     ${CMAKE_CURRENT_SOURCE_DIR}/*.mpirun=*.output)
foreach(_output ${_mpi_outputs})
  string(REGEX REPLACE "\\.mpirun=([0-9]+)\\.output$" "" _name ${_output})
  string(REGEX REPLACE "^.*\\.mpirun=([0-9]+)\\.output$" "\\1" _ranks
                       ${_output})
  foreach(_build release debug)
    set(_serial ${_category}/${_name}.${_build})
    set(_parallel ${_category}/${_name}.mpirun=${_ranks}.${_build})
    if(TEST ${_serial} AND TEST ${_parallel})
      set_tests_properties(${_serial} ${_parallel}
        PROPERTIES RESOURCE_LOCK ${_category}.${_name}.${_build}.executable)
    endif()
  endforeach()
endforeach()
