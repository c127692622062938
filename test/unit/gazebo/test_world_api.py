"""gazebo/world_api.py's answers when a request fails (no ROS master): the response says so in
its own fields, or a service error where it has none; never "did not answer" for an error."""
import time

import pytest
import rospy
from gazebo_msgs.srv import DeleteModel, SpawnModel
from std_srvs.srv import Empty

from tutorial_turtlebot.gazebo import sim_node, world_api
from tutorial_turtlebot.gazebo.loop_requests import LoopRequests


def test_a_failure_fills_success_and_status_message():
    response = world_api.failure(SpawnModel, "spawn_sdf_model: internal error: boom")
    assert response.success is False
    assert response.status_message == "spawn_sdf_model: internal error: boom"
    assert world_api.failure(DeleteModel, "x").success is False


def test_a_failure_of_a_response_without_fields_is_a_service_error():
    with pytest.raises(rospy.ServiceException, match="reset_world: internal error: boom"):
        world_api.failure(Empty, "reset_world: internal error: boom")


def Node():
    """A SimNode with only its request queue: what run_in_loop and queue_in_loop use."""
    node = object.__new__(sim_node.SimNode)
    node.requests = LoopRequests()
    return node


def api_over(node):
    api = object.__new__(world_api.WorldApi)
    api.node = node
    return api


def serve(node):
    """Run what is queued, as the loop does, until the caller has its answer."""
    import threading
    stop = threading.Event()

    def loop():
        while not stop.is_set():
            node.requests.wake.wait(0.05)
            node.requests.wake.clear()
            node.requests.run_pending()
    thread = threading.Thread(target=loop, daemon=True)
    thread.start()
    return stop


def test_an_internal_error_is_named_in_the_answer_and_the_next_request_is_served():
    node = Node()
    api = api_over(node)
    stop = serve(node)
    try:
        broken = api._in_loop("delete_model", DeleteModel, lambda _req: 1 / 0)
        answer = broken(DeleteModel._request_class(model_name="x"))
        assert answer.success is False
        assert answer.status_message == ("delete_model: internal error: ZeroDivisionError: "
                                         "division by zero")
        fine = api._in_loop("delete_model", DeleteModel,
                            lambda _req: DeleteModel._response_class(True, "ok"))
        assert fine(DeleteModel._request_class(model_name="x")).success is True
    finally:
        stop.set()


def test_a_request_the_loop_never_started_says_nothing_was_done(monkeypatch):
    monkeypatch.setattr(world_api, "ANSWER_TIMEOUT", 0.2)
    node = Node()                                   # no loop serves it
    ran = []
    call = api_over(node)._in_loop("delete_model", DeleteModel, lambda _req: ran.append(1))
    answer = call(DeleteModel._request_class(model_name="x"))
    assert answer.success is False
    assert answer.status_message == ("delete_model: the simulation did not answer within 0.2 s;"
                                     " nothing was done")
    node.requests.run_pending()                     # the loop comes back later: nothing runs
    assert ran == []


def test_the_empty_services_run_in_the_loop_and_name_their_failures(monkeypatch):
    """reset_simulation, reset_world, pause_physics, unpause_physics: EmptyResponse once the
    loop ran the action; a service error naming an internal error or a loop that did not answer
    (then the action never runs)."""
    from std_srvs.srv import EmptyResponse
    node = Node()
    api = api_over(node)
    ran = []
    logged = []
    monkeypatch.setattr(world_api.rospy, "logerr", lambda *args: logged.append(args[0] % args[1:]))
    stop = serve(node)
    try:
        assert api._empty_service("reset_world", lambda: ran.append(1))(None) == EmptyResponse()
        assert ran == [1]
        with pytest.raises(rospy.ServiceException) as err:
            api._empty_service("reset_simulation", lambda: 1 / 0)(None)
        assert str(err.value) == ("reset_simulation: internal error: ZeroDivisionError: "
                                  "division by zero")
        assert logged == ["reset_simulation: internal error: ZeroDivisionError: division by zero"]
    finally:
        stop.set()
    time.sleep(0.2)                                 # the loop has ended
    monkeypatch.setattr(world_api, "ANSWER_TIMEOUT", 0.2)
    with pytest.raises(rospy.ServiceException) as err:
        api._empty_service("pause_physics", lambda: ran.append(2))(None)
    assert str(err.value) == ("pause_physics: the simulation loop did not answer within 0.2 s; "
                              "nothing was done")
    time.sleep(0.1)
    assert ran == [1]
