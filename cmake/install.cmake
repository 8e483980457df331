# `cmake --install build --prefix P`: the constitutive model (sffcal::model, with its parameter
# file reader and the UMAT entry sffcal_umat), the UMAT shared library for Abaqus (sffcal::umat,
# umat_), the one for CalculiX (sffcal::umat_calculix, umat_ without DROT) and the deal.II
# material interface (sffcal::fe_model), their headers and a CMake package:
#   find_package(sffcal CONFIG REQUIRED)   # HINTS P/lib/cmake/sffcal, or CMAKE_PREFIX_PATH=P
# The model's interface needs only Eigen; sffcal::fe_model needs deal.II (found by the package).
include(CMakePackageConfigHelpers)

set(sffcal_install_targets sffcal_model sffcal_umat sffcal_umat_calculix)
install(FILES
  model/include/model/acst_model.h
  model/include/model/parameter_field.h
  model/include/model/update_status.h
  model/include/model/parameter_file.h
  model/include/model/descriptor.h
  model/include/model/point_driver.h
  model/include/model/batch_update.h
  model/include/model/acst_model_impl.h
  model/include/model/acst_implicit.h
  model/include/model/umat.h
  model/include/model/network_model.h
  model/include/model/network_tensor.h
  model/include/model/network_update.h
  model/include/model/umat_network.h
  DESTINATION include/model)
set(SFFCAL_INSTALL_FE_MODEL OFF)
if(TARGET fe_model)
  list(APPEND sffcal_install_targets fe_model)
  set(SFFCAL_INSTALL_FE_MODEL ON)
  install(FILES
    fe_model/include/fe_model/material.h
    fe_model/include/fe_model/solver_options.h
    fe_model/include/fe_model/solid.h
    fe_model/include/fe_model/triaxial.h
    fe_model/include/fe_model/model_material.h
    fe_model/include/fe_model/acst_material.h
    fe_model/include/fe_model/network_material.h
    DESTINATION include/fe_model)
endif()

install(TARGETS ${sffcal_install_targets} EXPORT sffcalTargets
  ARCHIVE DESTINATION lib LIBRARY DESTINATION lib RUNTIME DESTINATION bin)
install(EXPORT sffcalTargets NAMESPACE sffcal:: DESTINATION lib/cmake/sffcal)
configure_package_config_file(cmake/sffcalConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/sffcalConfig.cmake INSTALL_DESTINATION lib/cmake/sffcal)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/sffcalConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/sffcalConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/sffcalConfigVersion.cmake DESTINATION lib/cmake/sffcal)
