-- Executions in a room of robots (bench/e2e/fleet_load.sh; tests/db/fleet_report_test.cpp):
-- every frame a robot executed (a reception whose event is 'command': not a repeat, a
-- renewal, a synchronisation or a refusal) must be one some sender sent to that robot's
-- address, or to every robot, the same bits, heard between its chord's start and 3 s after
-- its end (the senders and robots share one clock). One row:
--   executed | executed by a robot it was not sent to | executed, sent by no sender
-- The second is a wrong robot's execution (another robot's frame); the third a wrong
-- execution (a corrupted frame that passed every check, or a stranger's). Targets: 0 and 0.
WITH executed AS (
  SELECT h.id, h.frame, h.frame_width, h.heard_at, h.robot_address FROM receptions h WHERE h.event = 'command'
),
sent AS (
  SELECT a.frame, a.frame_width, a.chord_started_at AS from_at,
         coalesce(a.chord_ended_at, a.chord_started_at) + interval '3 seconds' AS until_at,
         c.robot_address, c.every_robot
  FROM frame_attempts a JOIN commands c ON c.id = a.command_id
),
judged AS (
  SELECT e.id,
         EXISTS (SELECT 1 FROM sent s WHERE s.frame = e.frame AND s.frame_width = e.frame_width
                   AND e.heard_at BETWEEN s.from_at AND s.until_at
                   AND (s.robot_address = e.robot_address OR s.every_robot)) AS to_this_robot,
         EXISTS (SELECT 1 FROM sent s WHERE s.frame = e.frame AND s.frame_width = e.frame_width
                   AND e.heard_at BETWEEN s.from_at AND s.until_at) AS by_a_sender
  FROM executed e
)
SELECT count(*),
       count(*) FILTER (WHERE by_a_sender AND NOT to_this_robot),
       count(*) FILTER (WHERE NOT by_a_sender)
FROM judged;
