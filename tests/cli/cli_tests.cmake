message(STATUS "no cli tests yet")
