# The simulator's rolling ball against the ball model's constant deceleration (train friction).
nao_add_test(ball_roll_test SOURCES ball_roll_test.cpp LIBS nao_scenarios)
