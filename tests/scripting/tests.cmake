# Tests of scripting/.
