# gblens_layer(NAME FOLDER [VULKAN] [EXECUTABLE | SHARED] [COLD] DEPS layers... LINK targets... SOURCES files...)
# One folder = one library (gblens_NAME; the executable is `gblens`), with an explicit file list;
# COLD: code no figure's speed depends on, compiled at -O1 (cmake/BuildSpeed.cmake).
# DEPS are the layers whose headers the folder may include, and whose libraries it links (a SHARED
# library, the Vulkan layer loaded into other programs, links none: it compiles what it uses).
# gblens_write_layers() writes the table that cmake/check_includes.py checks every #include against.
set_property(GLOBAL PROPERTY GBLENS_LAYER_TABLE "")

function(gblens_layer NAME FOLDER)
  cmake_parse_arguments(L "VULKAN;EXECUTABLE;SHARED;COLD" "" "DEPS;LINK;SOURCES" ${ARGN})
  set(sources "")
  foreach(f ${L_SOURCES})
    if(IS_ABSOLUTE "${f}")
      list(APPEND sources "${f}")
    else()
      list(APPEND sources "${CMAKE_SOURCE_DIR}/${FOLDER}/${f}")
    endif()
  endforeach()
  if(L_EXECUTABLE)
    # The executable's files as an object library, so that they compile while the libraries they
    # link are still compiling (CMAKE_OPTIMIZE_DEPENDENCIES); `gblens` only links them.
    set(target gblens_${NAME})
    add_library(${target} OBJECT ${sources})
    gblens_pch(${target} cold)
    # Three batches, not two: the last files to compile are the executable's, and a shorter last
    # batch leaves the other core idle for less time.
    set_target_properties(${target} PROPERTIES UNITY_BUILD_BATCH_SIZE 7)
    add_executable(gblens)
    target_link_libraries(gblens PRIVATE ${target})
  elseif(L_SHARED)
    set(target gblens_${NAME})
    add_library(${target} SHARED ${sources})
    gblens_pch(${target} own)
  else()
    set(target gblens_${NAME})
    add_library(${target} STATIC ${sources})
    if(L_COLD)
      gblens_pch(${target} cold)
    else()
      gblens_pch(${target} library)
    endif()
  endif()
  set(folders "${FOLDER}")
  foreach(d ${L_DEPS})
    if(TARGET gblens_${d} AND NOT L_SHARED)
      target_link_libraries(${target} PUBLIC gblens_${d})
    endif()
    # Only layers declared above may be named, so the layers form no cycle.
    get_property(df GLOBAL PROPERTY GBLENS_LAYER_FOLDER_${d})
    if(NOT df)
      message(FATAL_ERROR "gblens_layer(${NAME}): DEPS names ${d}, which is no layer declared above it")
    endif()
    list(APPEND folders "${df}")
  endforeach()
  if(L_LINK)
    target_link_libraries(${target} PUBLIC ${L_LINK})
  endif()
  set_property(GLOBAL PROPERTY GBLENS_LAYER_FOLDER_${NAME} "${FOLDER}")
  set(vk "no")
  if(L_VULKAN)
    set(vk "yes")
  endif()
  list(JOIN folders " " allowed)
  set_property(GLOBAL APPEND_STRING PROPERTY GBLENS_LAYER_TABLE "${FOLDER}|${vk}|${allowed}\n")
endfunction()

function(gblens_write_layers)
  get_property(table GLOBAL PROPERTY GBLENS_LAYER_TABLE)
  file(WRITE ${CMAKE_BINARY_DIR}/layers.txt
       "# folder|may include Vulkan|folders it may include (written by cmake/Layers.cmake)\n${table}")
  add_test(NAME structure.includes
           COMMAND python3 ${CMAKE_SOURCE_DIR}/cmake/check_includes.py ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/layers.txt)
  set_tests_properties(structure.includes PROPERTIES LABELS unit)
endfunction()
