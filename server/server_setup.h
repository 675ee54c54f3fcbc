// dtmf-server's parts, made from its flags (server_flags.h) in the order main.cpp needs them:
// the security files first (a refused combination costs nothing), then the robots and their
// keys, the default profile, the audio devices, and at last the gRPC server. Each throws what
// stops the server, with what to do about it.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <utility>
#include <vector>

#include "bearer_token_auth.h"
#include "link/link.h"
#include "physical/audio_io.h"
#include "server_flags.h"
#include "transmitter.h"

namespace dtmf::server {

// The TLS files and the token, refused if others may read them, a blank token too (secret_file.h).
ServerSecurity read_security(const ServerFlags& f);

// The robots to drive: --robots FILE, else one robot from --robot-name, --robot-address,
// --key and --robot, each with its links (and so its key and counter store).
std::vector<RobotLinks> robot_links(const ServerFlags& f);

// The profile of commands that name none: --profile, or the default one of the robots' links
// (with a key, one whose frames carry a MAC; with several robots, one whose frames name them).
const LinkProfile& default_profile(const ServerFlags& f, const std::vector<RobotLinks>& robots);

// The loudspeaker and the microphone at `profile`'s rate.
std::pair<std::unique_ptr<physical::AudioSink>, std::unique_ptr<physical::AudioSource>> open_audio(
    const ServerFlags& f, const LinkProfile& profile);

// The gRPC server for `service`, with health, reflection and the UTF-8 check, serving; `port`
// the port it listens on.
std::unique_ptr<grpc::Server> start_serving(const ServerFlags& f,
                                            const std::shared_ptr<grpc::ServerCredentials>& credentials,
                                            grpc::Service& service, int& port);

}  // namespace dtmf::server
