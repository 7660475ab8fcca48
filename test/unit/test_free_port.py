"""free_port: a run's master gets a port that no bind to port 0 can be given first."""
import socket

from wall_follower.evaluation.launching import MASTER_PORTS_FROM, ephemeral_ports, free_port


def test_a_masters_port_lies_outside_the_ephemeral_range_and_binds():
    low, high = ephemeral_ports()
    for _ in range(50):
        port = free_port()
        assert port >= MASTER_PORTS_FROM and not low <= port <= high
        sock = socket.socket()
        try:
            sock.bind(('', port))
        finally:
            sock.close()


def test_a_bound_port_is_passed_over_and_with_none_left_any_free_port_will_do():
    # The range given leaves one port outside it, held here (or by someone else).
    only = MASTER_PORTS_FROM
    holder = socket.socket()
    try:
        try:
            holder.bind(('', only))
        except OSError:
            pass
        port = free_port(ephemeral=(only + 1, 65535))
    finally:
        holder.close()
    assert port > 0 and port != only
