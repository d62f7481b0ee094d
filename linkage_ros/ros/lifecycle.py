# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_lifecycle_node: suspension_node as a managed (lifecycle) node.

The same node (ros/node.SuspensionNode: its parameters, corners, topics, services and
recordings), made in the transitions of the ROS 2 lifecycle state machine (rclpy's
LifecycleNodeMixin), driven over the standard services <node>/change_state and
<node>/get_state:

    (start)     the parameters declared and checked (a mistake: exit status 2, as
                suspension_node); nothing loaded; state unconfigured
    configure   read the parameters, parse the scene or vehicle, compile the kernels (if
                numba's cache lacks them), open the recordings, create the publishers,
                subscriptions, the solve services and the diagnostics timer. A bad scene or
                vehicle (or output file) fails the transition with its one-line reason on the
                log; whatever was made is released and the node stays unconfigured.
    activate    answer: commands received from now on are solved and published
    deactivate  stop answering: commands are dropped unread, the solve service refuses;
                each corner keeps its pose (the next activate goes on from it)
    cleanup     release everything configure made (recordings closed); unconfigured again
    shutdown    stop answering, close the recordings; the process then exits with status 0

Parameters are read at configure: a change while configured is refused with that reason
(cleanup, set, configure again); unconfigured, a change is taken at the next configure.

Each transition is one line on the log: 'transition configure: unconfigured -> inactive' (an
INFO), or the reason it failed (an ERROR: 'configure failed: ...').
"""

from __future__ import annotations

from rcl_interfaces.msg import SetParametersResult
from rclpy.exceptions import ParameterException
from rclpy.lifecycle import LifecycleNodeMixin, TransitionCallbackReturn

from . import parameters
from .node import SuspensionNode


class ManagedSuspensionNode(LifecycleNodeMixin, SuspensionNode):
    """suspension_node, made at configure and answering only while active."""

    def __init__(self, sinks=(), before_solving=None, **kwargs) -> None:
        """
        Make the rclpy node and its lifecycle services; declare and check the parameters.

        sinks, before_solving: as SuspensionNode's, used at each configure. A bad parameter
        raises LinkageError (as suspension_node's start); a bad scene fails configure.
        """
        self._begin(kwargs)
        LifecycleNodeMixin.__init__(self)
        self.taking_commands = False
        self.finished = False           # shut down: the process may end
        self._made = None               # the entities there were before configure
        self.configured = False         # configured (inactive or active)
        self._sinks, self._before_solving = list(sinks), before_solving
        try:
            params = parameters.declare(self)
            self._take_clock_in_order(params['qos_depth'])
        except BaseException:
            super().destroy_node()
            raise
        self.add_on_set_parameters_callback(self._refuse_while_configured)

    def _refuse_while_configured(self, changes):
        # configure itself declares some (qos_overrides of the topics it makes)
        if not self.configured:
            return SetParametersResult(successful=True)
        return SetParametersResult(successful=False, reason=(
            'the parameters are read at configure: cleanup, set them, then configure again'))

    def _entities(self) -> set:
        return {*self.publishers, *self.subscriptions, *self.services, *self.timers,
                *self.clients}

    def on_configure(self, state) -> TransitionCallbackReturn:
        """Parse, compile and create everything; a mistake fails with its reason."""
        self._made = self._entities()
        try:
            params = self._wire(self._sinks, self._before_solving, clock=False)
        except (ValueError, OSError, ImportError, ParameterException) as exc:
            # LinkageError (a ValueError): its message names the file, field or parameter.
            self.get_logger().error(f'configure failed: {exc}')
            self._release()
            return TransitionCallbackReturn.FAILURE
        self._start(params)
        self.configured = True
        return self._done('configure', state, 'inactive')

    def on_activate(self, state) -> TransitionCallbackReturn:
        """Answer commands from now on."""
        self.taking_commands = True
        return self._done('activate', state, 'active', super().on_activate(state))

    def on_deactivate(self, state) -> TransitionCallbackReturn:
        """Drop commands from now on; the corners keep their poses."""
        self.taking_commands = False
        return self._done('deactivate', state, 'inactive', super().on_deactivate(state))

    def on_cleanup(self, state) -> TransitionCallbackReturn:
        """Release what configure made: recordings closed, topics and services gone."""
        self._release()
        return self._done('cleanup', state, 'unconfigured')

    def on_shutdown(self, state) -> TransitionCallbackReturn:
        """Stop answering and close the recordings; the process may end."""
        self.stop_taking_commands()
        self.close_sinks()
        self.finished = True
        return self._done('shutdown', state, 'finalized')

    def _done(self, transition, state, reached,
              result=TransitionCallbackReturn.SUCCESS) -> TransitionCallbackReturn:
        """Say a transition from state that succeeded (result) in one line; return result."""
        if result == TransitionCallbackReturn.SUCCESS:
            self.get_logger().info(f'transition {transition}: {state.label} -> {reached}')
        return result

    def on_error(self, state) -> TransitionCallbackReturn:
        """Release everything after a transition that raised: unconfigured again."""
        self.get_logger().error(f'a transition from {state.label} failed: released')
        self._release()
        return TransitionCallbackReturn.SUCCESS

    def _release(self) -> None:
        """Destroy every entity made since configure began; close the sinks."""
        self.taking_commands = False
        self.close_services()
        self.sinks.close()
        if self.tf_outputs is not None:
            self.tf_outputs.close()
            self.tf_outputs = None
        made = self._made or set()
        for entity in self._entities() - made:
            destroy = {'Publisher': self.destroy_publisher,
                       'Subscription': self.destroy_subscription,
                       'Service': self.destroy_service, 'Timer': self.destroy_timer,
                       'Client': self.destroy_client}
            destroy[type(entity).__name__](entity)
        self.corners, self.solve_services, self._made = {}, {}, None
        self.configured = False
        self.sinks = type(self.sinks)([], self._sink_failed, self.get_logger().error)

    def destroy_node(self):
        """
        Destroy the node, then its lifecycle state machine.

        rclpy leaves the state machine to the garbage collector, which may run it in a forked
        child (a multiprocessing pool) where finalizing it crashes the child: it is destroyed
        here, once the node is.
        """
        super().destroy_node()
        self._state_machine.destroy_when_not_in_use()


__all__ = ['ManagedSuspensionNode']
