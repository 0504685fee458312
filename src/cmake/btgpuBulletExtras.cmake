# btgpuBulletExtras.cmake — Bullet's .bullet file loader for btgpu_compare (demos/compare/):
# Debian's libbullet-extras-dev ships no pkg-config file, so its float libraries
# (libBulletWorldImporter.so, libBulletFileLoader.so; the -float64 ones are the double build)
# are found beside the float Bullet that pkg-config's "bullet" names. Defines the target
# btgpu_bullet_extras when they are there; the tool and its test are skipped when not.
find_library(BTGPU_BULLET_WORLD_IMPORTER NAMES BulletWorldImporter HINTS ${BTGPU_BULLET_LIBRARY_DIRS})
find_library(BTGPU_BULLET_FILE_LOADER NAMES BulletFileLoader HINTS ${BTGPU_BULLET_LIBRARY_DIRS})
find_path(BTGPU_BULLET_EXTRAS_INCLUDE BulletWorldImporter/btBulletWorldImporter.h
          HINTS ${BTGPU_BULLET_INCLUDE_DIRS} PATH_SUFFIXES bullet)
if(BTGPU_BULLET_WORLD_IMPORTER AND BTGPU_BULLET_FILE_LOADER AND BTGPU_BULLET_EXTRAS_INCLUDE)
  add_library(btgpu_bullet_extras INTERFACE IMPORTED GLOBAL)
  target_include_directories(btgpu_bullet_extras INTERFACE ${BTGPU_BULLET_EXTRAS_INCLUDE})
  target_link_libraries(btgpu_bullet_extras INTERFACE ${BTGPU_BULLET_WORLD_IMPORTER} ${BTGPU_BULLET_FILE_LOADER} btgpu_bullet)
else()
  message(STATUS "btgpu_compare not built: Bullet's world importer (Debian: libbullet-extras-dev) not found")
endif()
