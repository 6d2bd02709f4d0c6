# CMake helpers of the imagenets packages (catkin CFG_EXTRAS: every package that finds imagenets
# gets them).

# Each shared library names every library it uses (-Wl,--no-undefined), so the layering (engine
# without nodelet, library without blocks) is checked when it links. Not in sanitizer builds
# (scripts/fuzz, scripts/sanitizer-build): their runtime is linked by the executables only.
function(imagenets_no_undefined target)
  if(NOT CMAKE_CXX_FLAGS MATCHES "-fsanitize")
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
endfunction()

# Block libraries register their blocks when they load: a program or test that uses blocks by
# type name only, no symbol, keeps every library it links (no --as-needed).
function(imagenets_keep_linked target)
  target_link_options(${target} PRIVATE LINKER:--no-as-needed)
endfunction()

# Benchmarks are not part of `all`: `make bench` builds the target `benchmarks`.
if(NOT TARGET benchmarks)
  add_custom_target(benchmarks)
endif()

# `program` (an executable target of the package, in its devel folder as rosrun expects) also
# under the name `file` in the workspace's bin/, which setup.bash puts on PATH: the `imagenets`
# tool, and every `imagenets-NAME` program that `imagenets NAME` runs (imagenets/tool/command.h).
# Installed likewise (the package installs the target itself): a link in bin/.
function(imagenets_program_on_path target file)
  set_target_properties(${target} PROPERTIES OUTPUT_NAME ${file})
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_BIN_DESTINATION}
    COMMAND ${CMAKE_COMMAND} -E create_symlink $<TARGET_FILE:${target}>
            ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_BIN_DESTINATION}/${file})
  install(CODE "file(MAKE_DIRECTORY \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CATKIN_GLOBAL_BIN_DESTINATION}\")
    execute_process(COMMAND \"${CMAKE_COMMAND}\" -E create_symlink ../${CATKIN_PACKAGE_BIN_DESTINATION}/${file}
      \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CATKIN_GLOBAL_BIN_DESTINATION}/${file}\")")
endfunction()
