"""The installed package: where it came from, and its stubs against proto/ as it is now."""

import subprocess
import sys
from pathlib import Path

from google.protobuf import descriptor_pb2

import dtmf_teleop
from dtmf_teleop._stubs.dtmf.v1 import teleop_pb2, teleop_pb2_grpc

from conftest import REPO


def test_the_package_is_the_installed_one_not_the_source_tree():
    installed = Path(dtmf_teleop.__file__).resolve()
    assert Path(sys.prefix).resolve() in installed.parents
    assert (REPO / "clients" / "python" / "src") not in installed.parents


def test_the_generated_stubs_match_proto_exactly(tmp_path):
    descriptor_set = tmp_path / "teleop.pb"
    subprocess.run(["protoc", f"--proto_path={REPO / 'proto'}", f"--descriptor_set_out={descriptor_set}",
                    "dtmf/v1/teleop.proto"], check=True)
    expected = descriptor_pb2.FileDescriptorSet.FromString(descriptor_set.read_bytes()).file[0]
    for message in expected.message_type:  # the embedded copy leaves out the derivable json names
        for field in message.field:
            field.ClearField("json_name")
    built = descriptor_pb2.FileDescriptorProto.FromString(teleop_pb2.DESCRIPTOR.serialized_pb)
    assert built == expected


def test_every_rpc_has_a_stub_method():
    service = teleop_pb2.DESCRIPTOR.services_by_name["TeleopService"]
    stub_methods = {name for name in dir(teleop_pb2_grpc.TeleopServiceServicer) if not name.startswith("_")}
    assert {m.name for m in service.methods} == stub_methods
    assert len(service.methods) >= 10
