# ctest example.OmplPlanWritesPathAndPicture: runs the planning example (examples/ompl_plan.cpp)
# with the discrete validator (about a second) and checks what it writes: the path JSON has a
# solved run with a path, and the picture is an SVG document (starts with the XML prolog, has an
# <svg> root and ends by closing it). Usage:
#   cmake -DPLAN=<fcl_quadric_ompl_plan> -DOUT=<directory> -P ompl_plan_picture.cmake
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
execute_process(COMMAND "${PLAN}" --validator discrete --seed 2 --time 30 --out "${OUT}/path.json"
                        --picture "${OUT}/path.svg"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "fcl_quadric_ompl_plan exited with ${status}: ${err}")
endif()
file(READ "${OUT}/path.json" json)
string(JSON solved GET "${json}" discrete solved)
string(JSON waypoints LENGTH "${json}" discrete path)
if(NOT solved OR waypoints LESS 2)
  message(FATAL_ERROR "no solved path in ${OUT}/path.json: solved=${solved}, ${waypoints} waypoints")
endif()
file(READ "${OUT}/path.svg" svg)
string(STRIP "${svg}" svg)
string(FIND "${svg}" "<?xml" prolog)
string(FIND "${svg}" "<svg" root)
string(LENGTH "${svg}" n)
math(EXPR tail_at "${n} - 6")
string(SUBSTRING "${svg}" ${tail_at} 6 tail)
if(NOT prolog EQUAL 0 OR root LESS 0 OR NOT tail STREQUAL "</svg>")
  message(FATAL_ERROR "${OUT}/path.svg is not an SVG document (prolog at ${prolog}, <svg at ${root}, ends with '${tail}')")
endif()
message(STATUS "path with ${waypoints} waypoints; picture ${OUT}/path.svg (${n} bytes)")
