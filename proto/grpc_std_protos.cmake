# gRPC's standard health and reflection protos, from Debian's grpc-proto, compiled to C++.
#   grpc_health_proto: grpc.health.v1 messages and stubs. dtmf-server links it so that the
#     descriptors of grpc.health.v1.Health are in protobuf's generated pool: gRPC's built-in
#     health service is written without them, and reflection (grpcurl, buf curl) could list
#     the service but not describe or call it.
#   grpc_std_clients: that plus the v1alpha reflection client, for dtmfctl health and for
#     tests that check what grpcurl and health probes see. Never link it into a program that
#     also links gRPC::grpc++_reflection: both would register reflection.proto.
set(GRPC_PROTO_DIR /usr/share/grpc-proto)
set(STD_GEN ${CMAKE_CURRENT_BINARY_DIR}/std_gen)
function(dtmf_grpc_std_proto target proto)
  string(REPLACE ".proto" "" base ${proto})
  set(srcs ${STD_GEN}/${base}.pb.cc ${STD_GEN}/${base}.grpc.pb.cc)
  add_custom_command(
    OUTPUT ${srcs}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${STD_GEN}
    COMMAND protobuf::protoc --proto_path=${GRPC_PROTO_DIR} --cpp_out=${STD_GEN} --grpc_out=${STD_GEN}
            --plugin=protoc-gen-grpc=$<TARGET_FILE:gRPC::grpc_cpp_plugin> ${proto}
    WORKING_DIRECTORY ${GRPC_PROTO_DIR}
    COMMENT "protoc: ${proto}")
  add_library(${target} STATIC ${srcs})
  target_include_directories(${target} SYSTEM PUBLIC ${STD_GEN})
  target_link_libraries(${target} PUBLIC gRPC::grpc++ protobuf::libprotobuf)
endfunction()
dtmf_grpc_std_proto(grpc_health_proto grpc/health/v1/health.proto)
dtmf_grpc_std_proto(grpc_reflection_proto grpc/reflection/v1alpha/reflection.proto)
add_library(grpc_std_clients INTERFACE)
target_link_libraries(grpc_std_clients INTERFACE grpc_health_proto grpc_reflection_proto)
