# PERIFLEX_SANITIZE=address -> AddressSanitizer + UndefinedBehaviorSanitizer
# PERIFLEX_SANITIZE=thread  -> ThreadSanitizer
if(PERIFLEX_SANITIZE STREQUAL "address")
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
elseif(PERIFLEX_SANITIZE STREQUAL "thread")
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
elseif(PERIFLEX_SANITIZE)
  message(FATAL_ERROR "PERIFLEX_SANITIZE must be empty, 'address' or 'thread', not '${PERIFLEX_SANITIZE}'")
endif()
