# Embeds the shipped data files (assets/) into a generated source (renderer/core/assets.h), so the
# binary carries them. GBLENS_ASSETS lists them explicitly; the source is regenerated when one changes.
set(GBLENS_ASSETS layouts/gblens.json layouts/blender-cycles.json layouts/blender-cycles-sequence.json layouts/vkcube.json
    layouts/visibility-buffer.json)
set(GBLENS_ASSETS_SOURCE ${CMAKE_BINARY_DIR}/generated/assets.cpp)
set(asset_paths "")
foreach(a ${GBLENS_ASSETS})
  list(APPEND asset_paths ${CMAKE_SOURCE_DIR}/assets/${a})
endforeach()
add_custom_command(
  OUTPUT ${GBLENS_ASSETS_SOURCE}
  COMMAND ${CMAKE_COMMAND} -DROOT=${CMAKE_SOURCE_DIR}/assets "-DFILES=${GBLENS_ASSETS}" -DOUT=${GBLENS_ASSETS_SOURCE}
          -P ${CMAKE_SOURCE_DIR}/cmake/EmbedAssets.cmake
  DEPENDS ${asset_paths} ${CMAKE_SOURCE_DIR}/cmake/EmbedAssets.cmake
  COMMENT "embedding assets" VERBATIM)
