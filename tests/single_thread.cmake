# Every test of a directory runs on one thread, as each of fidus's MPI ranks
# does: the cut finite element, which runs on one rank, otherwise takes the
# machine's cores as threads while ctest runs other tests beside it, and
# the golden outputs were written on one thread (threads sum in another
# order). cli.cut_box runs the threaded solver against the single-threaded
# one. Include at the end of a directory's CMakeLists.txt.
get_property(_tests DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} PROPERTY TESTS)
foreach(_test ${_tests})
  set_property(TEST ${_test} APPEND PROPERTY ENVIRONMENT DEAL_II_NUM_THREADS=1)
endforeach()
