# Writes docs/SCENES.md and media/scenes/scene.schema.json from the scene-key table, through
# `ranryu scenes --markdown` and `--schema` (BIN: the ranryu binary; SOURCE_DIR: the repository).
foreach(pair "--markdown;docs/SCENES.md" "--schema;media/scenes/scene.schema.json")
  list(GET pair 0 option)
  list(GET pair 1 file)
  execute_process(COMMAND ${BIN} scenes ${option} OUTPUT_FILE ${SOURCE_DIR}/${file}.tmp RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    file(REMOVE ${SOURCE_DIR}/${file}.tmp)
    message(FATAL_ERROR "ranryu scenes ${option} failed (${rc})")
  endif()
  file(RENAME ${SOURCE_DIR}/${file}.tmp ${SOURCE_DIR}/${file})
  message(STATUS "wrote ${file}")
endforeach()
