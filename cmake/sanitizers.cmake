# VM_SANITIZE: a comma-separated list of GCC/Clang sanitizers (address,undefined or
# thread) compiled into every target of this build -- library, CLI, plugins, tests,
# examples -- so a finding anywhere fails the test that triggers it.
# scripts/test_sanitizers.sh configures, builds and tests these builds (.ci/sanitizers).
set(VM_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined or thread")

if(VM_SANITIZE)
  if(VM_SANITIZE MATCHES "thread" AND VM_SANITIZE MATCHES "address")
    message(FATAL_ERROR "VM_SANITIZE: thread and address cannot be combined")
  endif()
  # -fno-sanitize-recover: undefined behaviour aborts the test instead of printing a
  # line nobody reads. Frame pointers give whole stacks in the reports.
  add_compile_options(-fsanitize=${VM_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${VM_SANITIZE})
  message(STATUS "Sanitizers: ${VM_SANITIZE}")
endif()
