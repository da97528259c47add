#define FROM_HEADER 5
int header = __LINE__ + FROM_HEADER;
