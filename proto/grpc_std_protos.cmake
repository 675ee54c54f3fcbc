# C++ clients of gRPC's standard health and reflection services, from Debian's grpc-proto,
# for dtmfctl health and for tests that check what grpcurl and health probes see.
set(GRPC_PROTO_DIR /usr/share/grpc-proto)
set(STD_GEN ${CMAKE_CURRENT_BINARY_DIR}/std_gen)
set(STD_PROTOS grpc/health/v1/health.proto grpc/reflection/v1alpha/reflection.proto)
set(STD_SRCS)
foreach(proto ${STD_PROTOS})
  string(REPLACE ".proto" "" base ${proto})
  list(APPEND STD_SRCS ${STD_GEN}/${base}.pb.cc ${STD_GEN}/${base}.grpc.pb.cc)
endforeach()
add_custom_command(
  OUTPUT ${STD_SRCS}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${STD_GEN}
  COMMAND protobuf::protoc --proto_path=${GRPC_PROTO_DIR} --cpp_out=${STD_GEN} --grpc_out=${STD_GEN}
          --plugin=protoc-gen-grpc=$<TARGET_FILE:gRPC::grpc_cpp_plugin> ${STD_PROTOS}
  WORKING_DIRECTORY ${GRPC_PROTO_DIR}
  COMMENT "protoc: grpc health and reflection clients")
add_library(grpc_std_clients STATIC ${STD_SRCS})
target_include_directories(grpc_std_clients SYSTEM PUBLIC ${STD_GEN})
target_link_libraries(grpc_std_clients PUBLIC gRPC::grpc++ protobuf::libprotobuf)
