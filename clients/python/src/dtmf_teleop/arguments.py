"""The connection flags every dtmf_teleop script shares, matching dtmfctl's: --server
(default $DTMF_SERVER or localhost:50051), --tls-ca and --token-file."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from .client import DEFAULT_TARGET, Client


def add_connection_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--server", default=os.environ.get("DTMF_SERVER", DEFAULT_TARGET),
                        help="dtmf-server address host:port (default: $DTMF_SERVER or %(default)s)")
    parser.add_argument("--tls-ca", help="connect with TLS, trusting this PEM certificate")
    parser.add_argument("--token-file", help="send the bearer token in this file (dtmf-server --auth-token-file)")


def client_from_arguments(args: argparse.Namespace) -> Client:
    token = Path(args.token_file).read_text().strip() if args.token_file else None
    return Client(args.server, token=token, tls_ca=args.tls_ca)
