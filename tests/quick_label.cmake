# The quick subset (ctest -L quick, contrib/test.sh -L quick): the tests a
# developer runs after every edit: 33 tests, 55 s on 2 cores with
# everything built (measured 2026-12-04 at a1abc08; cli.bad_input is 53 s of it). They cover each module at its cheapest: the contact
# library (KKT conditions, pair search, glue), the time loop through the
# FluidModel interface with exact answers, the paper's 2D pair through the
# program with the three contact models, the run state, the Uzawa loop on
# its model problem, the cut element's coarse operators, the contact
# stress, bad input, the documentation and
# the style. Include after deal_ii_pickup_tests() with the names (without
# the .release suffix) in FIDUS_QUICK_TESTS.
get_filename_component(_category ${CMAKE_CURRENT_SOURCE_DIR} NAME)
foreach(_name ${FIDUS_QUICK_TESTS})
  foreach(_build release debug)
    if(TEST ${_category}/${_name}.${_build})
      set_tests_properties(${_category}/${_name}.${_build}
        PROPERTIES LABELS quick)
    endif()
  endforeach()
endforeach()
