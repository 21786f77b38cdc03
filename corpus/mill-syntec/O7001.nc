%@MACRO
// CALL-RUN-07A 子程序: M99 无引数
M99;
